// One tile of a frame: its pixels by the settings' anti-aliasing strategy
// (integrator/supersampling.h, corner_sampling.h, refine_sampling.h), then
// its AOVs from the first surface of a ray through each pixel centre.
// FrameRenderer (integrator/render.h) hands tiles to threads, each with its
// TileWorker.
#pragma once

#include <vector>

#include "integrator/corner_sampling.h"
#include "integrator/refine_sampling.h"
#include "integrator/supersampling.h"
#include "integrator/tile_sampling.h"

namespace quiver {

// Per-thread state: a tracer and its buffers, reused tile after tile.
struct TileWorker {
  SampleBatch batch;
  AdaptiveLattice adaptive;
  RefineBuffers refine;
  std::vector<Ray<float>> centre_rays;  // the AOVs' rays through pixel centres
  std::vector<FirstSurface> first;
  TileWorker(const Scene& scene, const SceneIntersector& intersector, const TraceSettings& settings)
      : batch(scene, intersector, settings) {}
};

class TileRenderer {
 public:
  // corners: the (W + 1) x (H + 1) corner colours of corners mode.
  TileRenderer(const TileTarget& target, std::vector<Vec3<float>>* corners);

  void render(const PixelTile& tile, TileWorker& w) const;

 private:
  void render_aovs(const PixelTile& tile, TileWorker& w) const;

  const TileTarget& target_;
  std::vector<Vec3<float>>* corners_;
  Supersampler supersampler_;
};

}  // namespace quiver
