// What the anti-aliasing strategies share, each in its own file
// (supersampling.h: none, grid, jitter; corner_sampling.h: corners,
// adaptive; refine_sampling.h: refine): the tile's target (camera,
// settings, image) and a worker's batch of camera samples, traced as one
// wavefront (tracer.h). A strategy writes only its tile's pixels, and
// every random number comes from a sample's pixel and number, so the
// image does not depend on the tile, the thread or the SIMD width.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "integrator/camera.h"
#include "integrator/render.h"
#include "integrator/tracer.h"

namespace quiver {

// A worker's tracer and its batch of camera samples, reused tile after tile.
struct SampleBatch {
  Tracer tracer;
  TraceStats stats;
  FilmSamples film;
  std::vector<Vec3<float>> colors;  // per sample of the last trace
  SampleBatch(const Scene& scene, const SceneIntersector& intersector, const TraceSettings& settings)
      : tracer(scene, intersector, settings) {}
};

// Where a tile's samples come from and its pixels go.
struct TileTarget {
  const Camera& camera;
  const RenderSettings& settings;
  Framebuffer& image;
  bool differentials;  // rays_carry_differentials (tracer.h)

  // Starts a batch of camera samples; cells are kept when rays carry differentials.
  void start_batch(SampleBatch& batch) const { batch.film.clear(differentials); }
  // Traces the batch into batch.colors (and, given, each sample's first surface).
  void trace(SampleBatch& batch, std::span<FirstSurface> surfaces = {}) const {
    batch.colors.resize(batch.film.size());
    batch.tracer.trace(camera, batch.film, batch.colors, batch.stats, surfaces);
  }
  void set_pixel(int x, int y, const Vec3<float>& c) const {
    float* p = &image.rgb[(std::size_t(y) * std::size_t(image.width) + std::size_t(x)) * 3];
    p[0] = c.x;
    p[1] = c.y;
    p[2] = c.z;
  }
};

}  // namespace quiver
