// quiver.camera_rays: the primary rays `quiver trace` casts for a scene, as
// arrays in its order: one ray through each pixel centre, 16x16 pixel tiles
// row by row, pixels in 4x4 groups inside a tile (app/trace_command.h). The
// tiles hold 256 rays each except at the right and bottom edges; tile_starts
// gives each tile's first ray, so the rays of an image whose sides are
// multiples of 16 fall into scene.intersect's batches exactly as trace's.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "app/trace_command.h"
#include "integrator/render.h"
#include "scene/scene_desc.h"

namespace quiver {

struct CameraRayPlan {
  CameraDesc camera;
  int width = 0, height = 0;
  std::vector<PixelTile> tiles;
  std::size_t ray_count() const { return std::size_t(width) * std::size_t(height); }
};

// The view and size trace would use with these options (check_trace_options
// first: throws UsageError as the CLI's flags do).
CameraRayPlan plan_camera_rays(const SceneDesc& desc, const TraceOptions& options);

// Fills ray_count() rows of origins and directions (x, y, z), pixels (x, y)
// and tiles.size() + 1 tile starts (the last is ray_count()).
void fill_camera_rays(const CameraRayPlan& plan, float* origins, float* directions, std::int32_t* pixels,
                      std::int64_t* tile_starts);

}  // namespace quiver
