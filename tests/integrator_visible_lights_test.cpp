// Area lights seen by camera, reflection and refraction rays
// (integrator/visible_lights.h): where rays meet a rectangle or sphere
// light, and what a render shows there.
#include <bit>
#include <cmath>
#include <cstdint>
#include <optional>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "integrator/render.h"
#include "integrator/visible_lights.h"
#include "scene/anti_aliasing.h"

namespace quiver {
namespace {

LightDesc rectangle_light() {
  LightDesc light;
  light.kind = LightDesc::Kind::rectangle;
  light.position = {-1.f, -1.f, 0.f};  // the corner; the square [-1, 1]^2 at z = 0
  light.edge_u = {2.f, 0.f, 0.f};
  light.edge_v = {0.f, 2.f, 0.f};
  light.color = {0.9f, 0.8f, 0.7f};
  return light;
}

Ray<float> ray(Vec3<float> origin, Vec3<float> direction) {
  return {origin, direction, 0.f, std::numeric_limits<float>::infinity()};
}

TEST(VisibleLights, ARectangleIsMetFromEitherSideInsideItsEdgesAndBeforeTheLimit) {
  const LightDesc light = rectangle_light();
  const float inf = std::numeric_limits<float>::infinity();
  EXPECT_EQ(area_light_distance(light, ray({0.5f, 0.5f, 4.f}, {0.f, 0.f, -1.f}), inf), std::optional<float>(4.f));
  EXPECT_EQ(area_light_distance(light, ray({0.5f, 0.5f, -2.f}, {0.f, 0.f, 2.f}), inf), std::optional<float>(1.f));
  EXPECT_FALSE(area_light_distance(light, ray({1.5f, 0.f, 4.f}, {0.f, 0.f, -1.f}), inf));  // beside it
  EXPECT_FALSE(area_light_distance(light, ray({0.f, 0.f, 4.f}, {0.f, 0.f, 1.f}), inf));    // away from it
  EXPECT_FALSE(area_light_distance(light, ray({0.f, 0.f, 4.f}, {0.f, 0.f, -1.f}), 3.f));   // a surface before it
  EXPECT_FALSE(area_light_distance(light, ray({0.f, 0.f, 4.f}, {1.f, 0.f, 0.f}), inf));    // parallel
  LightDesc skewed = light;  // a parallelogram: (a, b) solve along both edges
  skewed.edge_v = {1.f, 2.f, 0.f};
  EXPECT_TRUE(area_light_distance(skewed, ray({1.8f, 0.9f, 4.f}, {0.f, 0.f, -1.f}), inf));
  EXPECT_FALSE(area_light_distance(skewed, ray({-0.9f, 0.9f, 4.f}, {0.f, 0.f, -1.f}), inf));
}

TEST(VisibleLights, ASphereIsMetAtItsNearSideOrFromInsideAtItsFarSide) {
  LightDesc light;
  light.kind = LightDesc::Kind::sphere;
  light.position = {0.f, 0.f, 0.f};
  light.radius = 1.f;
  const float inf = std::numeric_limits<float>::infinity();
  EXPECT_EQ(area_light_distance(light, ray({0.f, 0.f, 5.f}, {0.f, 0.f, -1.f}), inf), std::optional<float>(4.f));
  EXPECT_EQ(area_light_distance(light, ray({0.f, 0.f, 0.f}, {0.f, 0.f, -1.f}), inf), std::optional<float>(1.f));
  EXPECT_FALSE(area_light_distance(light, ray({0.f, 2.f, 5.f}, {0.f, 0.f, -1.f}), inf));
  LightDesc point;
  point.position = {0.f, 0.f, 0.f};
  EXPECT_FALSE(area_light_distance(point, ray({0.f, 0.f, 5.f}, {0.f, 0.f, -1.f}), inf));
}

// A camera looking at a rectangle light over a mirror floor: the pixel on
// the light shows its colour, the pixel of its reflection kr times it, a
// sphere in front of the light hides it, and every unit agrees bit for bit.
TEST(VisibleLights, CameraAndReflectionRaysShowTheLightUnshaded) {
  SceneDesc desc;
  desc.camera = CameraDesc{{0.f, 0.f, 6.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 60.f, 0.f, 33, 33};
  desc.background = Vec3<float>{0.f, 0.f, 0.f};
  desc.ambient = {0.f, 0.f, 0.f};
  LightDesc light = rectangle_light();
  light.position = {-1.f, 0.5f, 0.f};  // [-1, 1] x [0.5, 2.5] at z = 0
  desc.lights.push_back(light);
  MaterialDesc mirror;
  mirror.kd = 0.f;
  mirror.ks = 0.f;
  mirror.kr = 0.5f;
  desc.materials = {mirror, MaterialDesc{}};
  desc.planes.push_back({{{0.f, -1.f, 0.f}, {0.f, 1.f, 0.f}}, 0});  // the mirror floor at y = -1
  desc.spheres.push_back({{{0.8f, 1.5f, 2.f}, 0.3f}, 1});           // in front of the light's right
  const Scene scene = build_scene(desc, {});
  RenderSettings settings;
  settings.width = settings.height = 33;
  settings.aa = parse_anti_aliasing("none");
  settings.aov_depth = true;
  settings.isa = Isa::scalar;
  const Framebuffer image = render(scene, settings).image;
  const Camera camera(*desc.camera, 33, 33);
  // The pixel whose centre ray meets the light at x = -0.5, y = 1.5.
  const auto pixel_of = [&](float x, float y, float z) {
    const double tangent = std::tan(30.0 * std::acos(-1.0) / 180.0);
    const double px = 16.0 + x / (6.0 - z) / tangent * 16.0, py = 16.0 - y / (6.0 - z) / tangent * 16.0;
    return std::size_t(std::lround(py - 0.5)) * 33 + std::size_t(std::lround(px - 0.5));
  };
  const std::size_t on_light = pixel_of(-0.5f, 1.5f, 0.f);
  EXPECT_EQ(image.rgb[3 * on_light], 0.9f);
  EXPECT_EQ(image.rgb[3 * on_light + 1], 0.8f);
  EXPECT_EQ(image.rgb[3 * on_light + 2], 0.7f);
  EXPECT_FALSE(std::isfinite(image.depth[on_light]));  // a light is not a surface for the AOVs
  // The sphere hides the light behind it: shaded, not the light's colour.
  const std::size_t on_sphere = pixel_of(0.8f, 1.5f, 2.3f);
  EXPECT_TRUE(std::isfinite(image.depth[on_sphere]));
  EXPECT_NE(image.rgb[3 * on_sphere], 0.9f);
  // Somewhere on the mirror, the light's reflection: kr times its colour.
  std::size_t reflected = 0;
  for (std::size_t p = 33 * 20; p < image.depth.size(); ++p) reflected += image.rgb[3 * p] == 0.5f * 0.9f;
  EXPECT_GT(reflected, 5u);
  for (const Isa isa : kIsas) {
    if (!isa_supported(isa)) continue;
    settings.isa = isa;
    EXPECT_EQ(render(scene, settings).image.rgb, image.rgb) << isa_name(isa);
  }
}

// see_area_lights in every unit against the one-lane test ray by ray:
// rays from a cube round the lights toward random points, some parallel to
// the rectangle, some stopped by a hit before a light; a point light among
// them sees nothing; a last partial packet whose last ray meets a light;
// the same t, ids and colours.
class VisibleLightsUnits : public ::testing::TestWithParam<KernelUnit> {};

TEST_P(VisibleLightsUnits, MeetTheLightsAsTheOneLaneTestRayByRay) {
  const KernelUnit unit = GetParam();
  if (!kernel_unit_supported(unit)) GTEST_SKIP() << "this CPU cannot run " << kernel_unit_name(unit);
  SceneDesc desc;
  LightDesc point;
  point.position = {0.f, 0.f, 1.f};
  LightDesc sphere;
  sphere.kind = LightDesc::Kind::sphere;
  sphere.position = {0.5f, 0.2f, -0.3f};
  sphere.radius = 0.6f;
  sphere.color = {0.2f, 0.4f, 0.6f};
  desc.camera = CameraDesc{{0.f, 0.f, 6.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 60.f, 0.f, 8, 8};
  desc.lights = {point, rectangle_light(), sphere};
  desc.materials = {MaterialDesc{}};
  desc.spheres.push_back({{{5.f, 5.f, 5.f}, 0.1f}, 0});
  const Scene scene = build_scene(desc, {});
  std::mt19937 random(7);
  std::uniform_real_distribution<float> coordinate(-3.f, 3.f);
  RaySoA rays;
  HitSoA hits;
  for (int i = 0; i < 203; ++i) {
    const Vec3<float> origin{coordinate(random), coordinate(random), coordinate(random)};
    Vec3<float> target{coordinate(random) / 3.f, coordinate(random) / 3.f, coordinate(random) / 3.f};
    if (i % 17 == 0) target.z = origin.z;  // parallel to the rectangle
    rays.push(Ray<float>{origin, target - origin, i % 5 == 0 ? 0.5f : 0.f, std::numeric_limits<float>::infinity()});
  }
  rays.push(Ray<float>{{0.2f, 0.3f, 4.f}, {0.f, 0.f, -1.f}, 0.f, 1e30f});  // the last ray meets the rectangle
  rays.pad();
  hits.reset(rays);
  for (std::size_t i = 0; i + 1 < rays.count; i += 3) {  // a surface met first at t in (0, 1.2)
    hits.t[i] = 0.2f + 0.01f * float(i % 100);
    hits.id[i] = 7;
  }
  Vec3Columns seen;
  for (AlignedFloats* c : seen.columns()) c->assign(rays.ox.size(), 0.125f);
  HitSoA expected_hits = hits;
  Vec3Columns expected_seen = seen;
  std::size_t met = 0;
  for (std::size_t i = 0; i < rays.count; ++i) {
    for (const LightDesc& light : scene.lights) {
      const std::optional<float> t = area_light_distance(light, rays.get(i), expected_hits.t[i]);
      if (!t) continue;
      expected_hits.t[i] = *t;
      expected_hits.id[i] = kNoHit;
      expected_seen.set(i, light.color);
      ++met;
    }
  }
  ASSERT_GT(met, 40u);
  with_kernel_unit(unit, [&](auto u) { see_area_lights<decltype(u)::value>(scene, rays, hits, seen); });
  for (std::size_t i = 0; i < rays.count; ++i) {
    const std::string where = std::string(kernel_unit_name(unit)) + " ray " + std::to_string(i);
    EXPECT_EQ(std::bit_cast<std::uint32_t>(hits.t[i]), std::bit_cast<std::uint32_t>(expected_hits.t[i])) << where;
    EXPECT_EQ(hits.id[i], expected_hits.id[i]) << where;
    EXPECT_EQ(seen.get(i)[0], expected_seen.get(i)[0]) << where;
    EXPECT_EQ(seen.get(i)[1], expected_seen.get(i)[1]) << where;
    EXPECT_EQ(seen.get(i)[2], expected_seen.get(i)[2]) << where;
  }
}

INSTANTIATE_TEST_SUITE_P(EveryUnit, VisibleLightsUnits, ::testing::ValuesIn(kKernelUnits),
                         [](const ::testing::TestParamInfo<KernelUnit>& info) {
                           return std::string(kernel_unit_name(info.param));
                         });

}  // namespace
}  // namespace quiver
