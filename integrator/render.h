// A whole image: the film cut into tiles, each tile's camera samples traced
// as one wavefront batch (integrator/tracer.h), tiles spread over the cores
// with oneTBB. Each tile writes only its own pixels and every random number
// comes from the sample's film position, so the image is the same for any
// thread count, tile order and SIMD width.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "integrator/anti_aliasing.h"
#include "integrator/framebuffer.h"
#include "scene/scene.h"
#include "integrator/trace_stats.h"
#include "integrator/tracer.h"
#include "simd/isa.h"

namespace quiver {

struct RenderSettings {
  int width = 512, height = 512;
  AntiAliasing aa;
  TraceSettings trace;
  int threads = 0;  // 0: every core
  Isa isa = Isa::scalar;
  bool aov_depth = false, aov_normal = false, aov_id = false;  // id also writes the kind
  int tile_size = 16;
  MethodChoice methods = MethodChoice::per_scene;  // most_robust: robust sphere test in every scene
};

struct RenderResult {
  Framebuffer image;
  TraceStats stats;
  double render_ms = 0.0;
  int threads = 0;  // threads actually used
  SphereMethod sphere_method = SphereMethod::robust;  // the one the render used
  std::size_t tiles_done = 0, tiles_total = 0;
  // The stop flag was seen: tiles not yet started were skipped, the image is incomplete.
  bool stopped() const { return tiles_done < tiles_total; }
};

// A rectangle of pixels: the renderer's unit of work.
struct PixelTile {
  int x0, y0, width, height;
};

// The pixels of [x0, x1) x [y0, y1) in groups of 4 x 4, the groups row by
// row, partial groups at the right and bottom edges. Traced in this order,
// 16 consecutive samples (one 16-wide packet) cover a 4 x 4 footprint and
// eight (one 8-wide packet) a 4 x 2 footprint, not a row, and stay closer
// together through the BVH (bench/README.md).
inline constexpr int kPixelGroupWidth = 4, kPixelGroupHeight = 4;
template <class Visit>
void for_each_pixel_in_groups(int x0, int y0, int x1, int y1, Visit&& visit) {
  for (int gy = y0; gy < y1; gy += kPixelGroupHeight) {
    for (int gx = x0; gx < x1; gx += kPixelGroupWidth) {
      for (int y = gy; y < std::min(gy + kPixelGroupHeight, y1); ++y) {
        for (int x = gx; x < std::min(gx + kPixelGroupWidth, x1); ++x) visit(x, y);
      }
    }
  }
}

// Tiles of at most side x side pixels covering width x height, row by row.
// Throws std::invalid_argument for side < 1.
std::vector<PixelTile> pixel_tiles(int width, int height, int side);

// Called after each tile with (tiles done, tiles total), from worker
// threads one at a time.
using RenderProgress = std::function<void(std::size_t done, std::size_t total)>;

// stop, when given, is read before each tile: once it is true no further
// tile starts and the result says stopped (a signal handler may set it).
RenderResult render(const Scene& scene, const RenderSettings& settings, const RenderProgress& progress = {},
                    const std::atomic<bool>* stop = nullptr);

}  // namespace quiver
