// Surface details (integrator/surface.h): texture coordinates at points
// whose mapping is known by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "integrator/scene_intersector.h"
#include "integrator/surface.h"

namespace quiver {
namespace {

// The sphere's (u, v) at the point of direction `out` from its centre, hit
// by a ray coming straight in.
std::pair<float, float> sphere_uv(const Vec3<float>& out) {
  SceneDesc d;
  d.camera = CameraDesc{{0.f, 0.f, 20.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 45.f, 0.f, 8, 8};
  d.textures.push_back(TextureDesc{});  // a checker: texture coordinates are computed
  MaterialDesc textured;
  textured.texture = 0;
  d.materials.push_back(textured);
  const Vec3<float> centre{1.f, 2.f, 3.f};
  d.spheres.push_back({{centre, 2.f}, 0});
  const Scene scene = build_scene(d, {});
  const Vec3<float> unit = normalize(out);
  RaySoA rays;
  rays.push({centre + unit * 5.f, unit * -1.f, 0.f, std::numeric_limits<float>::infinity()});
  rays.pad();
  HitSoA hits(rays);
  SceneIntersector(KernelUnit::scalar).closest(scene, rays, hits);
  EXPECT_NE(hits.id[0], kNoHit);
  const SurfaceDetail s = surface_detail(scene, rays.get(0), hits.get(0));
  return {s.u, s.v};
}

TEST(SurfaceDetail, SphereCoordinatesAreLongitudeAndLatitudeTurningRightHandedAboutY) {
  const struct {
    Vec3<float> out;
    float u, v;
  } cases[] = {
      {{1.f, 0.f, 0.f}, 0.5f, 0.5f},     // +x: the middle of the map
      {{0.f, 0.f, -1.f}, 0.75f, 0.5f},   // a quarter turn about +y (right-handed) from +x
      {{0.f, 0.f, 1.f}, 0.25f, 0.5f},    // a quarter turn back
      {{1.f, 1.f, 0.f}, 0.5f, 0.75f},    // 45 degrees north
      {{1.f, -1.f, 0.f}, 0.5f, 0.25f},   // 45 degrees south
      {{-1.f, 0.f, -1.f}, 0.875f, 0.5f}  // three eighths of a turn
  };
  for (const auto& c : cases) {
    const auto [u, v] = sphere_uv(c.out);
    EXPECT_NEAR(u, c.u, 1e-6f) << c.out.x << "," << c.out.y << "," << c.out.z;
    EXPECT_NEAR(v, c.v, 1e-6f) << c.out.x << "," << c.out.y << "," << c.out.z;
  }
}

}  // namespace
}  // namespace quiver
