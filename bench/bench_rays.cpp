#include "bench/bench_rays.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "integrator/camera.h"
#include "integrator/optics.h"
#include "integrator/render.h"
#include "integrator/scene_intersector.h"
#include "integrator/surface.h"

namespace quiver::bench {

namespace {

constexpr int kTile = 16;

RaySoA to_soa(const std::vector<Ray<float>>& rays) {
  RaySoA soa(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) soa.set(i, rays[i]);
  soa.pad();
  return soa;
}

}  // namespace

SceneRays make_scene_rays(const Scene& scene, int width, int height, std::uint32_t seed) {
  const Camera camera(scene.camera, width, height);
  std::vector<Ray<float>> primary;
  for (const PixelTile& tile : pixel_tiles(width, height, kTile)) {
    for_each_pixel_in_groups(tile.x0, tile.y0, tile.x0 + tile.width, tile.y0 + tile.height,
                             [&](int x, int y) { primary.push_back(camera.ray(x + 0.5, y + 0.5)); });
  }
  SceneRays out;
  out.primary = to_soa(primary);
  HitSoA hits(out.primary);
  SceneIntersector(kernel_unit_for(best_supported_isa())).closest(scene, out.primary, hits);

  // A light above and behind the camera, at the scene's scale.
  const Vec3<float> extent = scene.bounds_max - scene.bounds_min;
  const float size = std::sqrt(dot(extent, extent));
  const Ray<float> centre = camera.ray(width * 0.5, height * 0.5);
  const Vec3<float> light = centre.origin - centre.direction * (0.5f * size) + Vec3<float>(0.f, size, 0.f);

  std::mt19937 rng(seed);
  std::normal_distribution<float> gauss;
  std::vector<Ray<float>> reflection, diffuse, shadow;
  const float inf = std::numeric_limits<float>::infinity();
  for (std::size_t i = 0; i < primary.size(); ++i) {
    const Hit<float> hit = hits.get(i);
    if (hit.id == kNoHit) continue;
    const SurfacePoint s = surface_at(scene, primary[i], hit);
    const Vec3<float> from = offset_origin(s.position, s.error, s.geometric);
    reflection.push_back({from, reflect(primary[i].direction, s.geometric), 0.f, inf});
    Vec3<float> d{gauss(rng), gauss(rng), gauss(rng)};
    if (dot(d, s.geometric) < 0.f) d = d * -1.f;
    diffuse.push_back({from, normalize(d), 0.f, inf});
    shadow.push_back({from, light - from, 0.f, 1.f});
  }
  out.reflection = to_soa(reflection);
  out.diffuse = to_soa(diffuse);
  out.shadow = to_soa(shadow);
  return out;
}

}  // namespace quiver::bench
