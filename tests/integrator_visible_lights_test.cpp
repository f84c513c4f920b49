// Area lights seen by camera, reflection and refraction rays
// (integrator/visible_lights.h): where rays meet a rectangle or sphere
// light, and what a render shows there.
#include <cmath>
#include <optional>
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

}  // namespace
}  // namespace quiver
