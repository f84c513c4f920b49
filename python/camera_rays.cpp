#include "python/camera_rays.h"

#include "integrator/camera.h"

namespace quiver {

CameraRayPlan plan_camera_rays(const SceneDesc& desc, const TraceOptions& options) {
  check_trace_options(options);
  SceneDesc viewed = desc;
  CameraRayPlan plan;
  std::tie(plan.width, plan.height) = set_trace_view(options, viewed);
  plan.camera = *viewed.camera;
  plan.tiles = pixel_tiles(plan.width, plan.height, kTraceTileSide);
  return plan;
}

void fill_camera_rays(const CameraRayPlan& plan, float* origins, float* directions, std::int32_t* pixels,
                      std::int64_t* tile_starts) {
  const Camera camera(plan.camera, plan.width, plan.height);
  RaySoA rays;
  std::size_t k = 0;
  for (std::size_t t = 0; t < plan.tiles.size(); ++t) {
    const PixelTile& tile = plan.tiles[t];
    tile_starts[t] = std::int64_t(k);
    tile_primary_rays(camera, tile, rays);
    std::size_t i = k;
    for_each_pixel_in_groups(tile.x0, tile.y0, tile.x0 + tile.width, tile.y0 + tile.height, [&](int x, int y) {
      pixels[2 * i] = x;
      pixels[2 * i + 1] = y;
      ++i;
    });
    for (std::size_t r = 0; r < rays.count; ++r, ++k) {
      const Ray<float> ray = rays.get(r);
      const float row_origin[3] = {ray.origin.x, ray.origin.y, ray.origin.z};
      const float row_direction[3] = {ray.direction.x, ray.direction.y, ray.direction.z};
      for (int c = 0; c < 3; ++c) {
        origins[3 * k + c] = row_origin[c];
        directions[3 * k + c] = row_direction[c];
      }
    }
  }
  tile_starts[plan.tiles.size()] = std::int64_t(k);
}

}  // namespace quiver
