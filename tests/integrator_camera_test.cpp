// The NFF pixel-ray convention: `angle` spans the centres of the outermost
// pixel columns; up need not be perpendicular; film y grows downward.
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "scene/anti_aliasing.h"
#include "integrator/camera.h"

namespace quiver {
namespace {

double degrees_between(const Vec3<float>& a, const Vec3<float>& b) {
  const double c = (double(a.x) * b.x + double(a.y) * b.y + double(a.z) * b.z) /
                   std::sqrt((double(a.x) * a.x + double(a.y) * a.y + double(a.z) * a.z) *
                             (double(b.x) * b.x + double(b.y) * b.y + double(b.z) * b.z));
  return std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

TEST(Camera, AngleSpansOutermostPixelCentres) {
  // Up (0, 1, 1) is not perpendicular to the view direction -z.
  const CameraDesc desc{{0.f, 0.f, 0.f}, {0.f, 0.f, -1.f}, {0.f, 1.f, 1.f}, 60.f, 0.f, 9, 9};
  const Camera camera(desc, 9, 9);
  const Ray<float> left = camera.ray(0.5, 4.5), right = camera.ray(8.5, 4.5);
  const Ray<float> top = camera.ray(4.5, 0.5), bottom = camera.ray(4.5, 8.5);
  EXPECT_NEAR(degrees_between(left.direction, right.direction), 60.0, 1e-4);
  EXPECT_NEAR(degrees_between(top.direction, bottom.direction), 60.0, 1e-4);
  const Ray<float> centre = camera.ray(4.5, 4.5);
  EXPECT_NEAR(centre.direction.z, -1.f, 1e-7f);
  EXPECT_GT(top.direction.y, 0.f);     // film y grows downward
  EXPECT_GT(right.direction.x, 0.f);   // and x to the right
  EXPECT_NEAR(top.direction.x, 0.f, 1e-7f);
}

TEST(Camera, DirectionDifferentialsMatchFiniteDifferencesOfTheRays) {
  const CameraDesc desc{{1.f, 2.f, 3.f}, {0.f, 0.5f, -4.f}, {0.2f, 1.f, 0.f}, 50.f, 0.f, 64, 48};
  const Camera camera(desc, 64, 48);
  for (const auto& [x, y] : {std::pair{0.5, 0.5}, std::pair{31.7, 20.2}, std::pair{63.5, 47.5}}) {
    for (double spacing : {1.0, 0.25}) {
      const Camera::DirectionDifferentials d = camera.direction_differentials(x, y, spacing);
      // Central differences over a small step, scaled to the spacing.
      const double h = 1e-3;
      const Ray<float> xp = camera.ray(x + h, y), xm = camera.ray(x - h, y);
      const Ray<float> yp = camera.ray(x, y + h), ym = camera.ray(x, y - h);
      const double k = spacing / (2.0 * h);
      EXPECT_NEAR(d.dx.x, (double(xp.direction.x) - xm.direction.x) * k, 2e-4 * spacing);
      EXPECT_NEAR(d.dx.y, (double(xp.direction.y) - xm.direction.y) * k, 2e-4 * spacing);
      EXPECT_NEAR(d.dx.z, (double(xp.direction.z) - xm.direction.z) * k, 2e-4 * spacing);
      EXPECT_NEAR(d.dy.x, (double(yp.direction.x) - ym.direction.x) * k, 2e-4 * spacing);
      EXPECT_NEAR(d.dy.y, (double(yp.direction.y) - ym.direction.y) * k, 2e-4 * spacing);
      EXPECT_NEAR(d.dy.z, (double(yp.direction.z) - ym.direction.z) * k, 2e-4 * spacing);
    }
  }
}

TEST(Camera, WiderSideCarriesTheAngleAndPixelsAreSquare) {
  const CameraDesc desc{{0.f, 0.f, 0.f}, {0.f, 0.f, -1.f}, {0.f, 1.f, 0.f}, 40.f, 0.f, 17, 9};
  const Camera camera(desc, 17, 9);
  EXPECT_NEAR(degrees_between(camera.ray(0.5, 4.5).direction, camera.ray(16.5, 4.5).direction), 40.0, 1e-4);
  // Tangent-plane steps are equal across and down.
  const Ray<float> c = camera.ray(8.5, 4.5), r = camera.ray(9.5, 4.5), d = camera.ray(8.5, 5.5);
  EXPECT_NEAR(r.direction.x / -r.direction.z, -(d.direction.y / -d.direction.z), 1e-6);
  EXPECT_NEAR(c.direction.x, 0.f, 1e-7f);
}

TEST(Camera, RejectsDegenerateViews) {
  EXPECT_THROW(Camera(CameraDesc{{0, 0, 0}, {0, 0, 0}, {0, 1, 0}, 45.f, 0.f, 4, 4}, 4, 4), std::invalid_argument);
  EXPECT_THROW(Camera(CameraDesc{{0, 0, 0}, {0, 1, 0}, {0, 2, 0}, 45.f, 0.f, 4, 4}, 4, 4), std::invalid_argument);
  EXPECT_THROW(Camera(CameraDesc{{0, 0, 0}, {0, 0, 1}, {0, 1, 0}, 180.f, 0.f, 4, 4}, 4, 4), std::invalid_argument);
  // A view direction of no finite length is no view, and the error names 'at'.
  const float inf = std::numeric_limits<float>::infinity();
  try {
    Camera(CameraDesc{{0, 0, 0}, {inf, 0, 1}, {0, 1, 0}, 45.f, 0.f, 4, 4}, 4, 4);
    ADD_FAILURE() << "an infinitely far 'at' made a camera";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'at'"), std::string::npos) << e.what();
  }
}

TEST(AntiAliasing, ParsesEveryModeAndRejectsTheRest) {
  EXPECT_EQ(parse_anti_aliasing("none").mode, AntiAliasing::Mode::none);
  EXPECT_EQ(parse_anti_aliasing("corners").mode, AntiAliasing::Mode::corners);
  EXPECT_EQ(parse_anti_aliasing("grid:3").n, 3);
  EXPECT_EQ(parse_anti_aliasing("jitter:4").mode, AntiAliasing::Mode::jitter);
  const AntiAliasing a = parse_anti_aliasing("adaptive:0.05:3");
  EXPECT_EQ(a.mode, AntiAliasing::Mode::adaptive);
  EXPECT_EQ(a.threshold, 0.05f);
  EXPECT_EQ(a.depth, 3);
  const AntiAliasing r = parse_anti_aliasing("refine:0.02:8");
  EXPECT_EQ(r.mode, AntiAliasing::Mode::refine);
  EXPECT_EQ(r.threshold, 0.02f);
  EXPECT_EQ(r.n, 8);
  EXPECT_EQ(r.strata, AntiAliasing::Strata::jitter);
  EXPECT_EQ(parse_anti_aliasing("refine:0.02:8:grid").strata, AntiAliasing::Strata::grid);
  EXPECT_EQ(parse_anti_aliasing("refine:0.02:8:jitter").strata, AntiAliasing::Strata::jitter);
  EXPECT_EQ(to_string(parse_anti_aliasing("refine:0.02:8:jitter")), "refine:0.02:8");
  for (const char* bad : {"", "grid", "grid:0", "grid:65", "jitter:x", "adaptive:0.1", "adaptive:-1:2",
                          "adaptive:nan:2", "adaptive:0.1:7", "corners:2", "none:1", "super", "refine",
                          "refine:0.1", "refine:0.1:1", "refine:0.1:6", "refine:0.1:32", "refine:-0.1:4", "refine:0.1:4:", "refine:0.1:4:shift",
                          "refine:0.1:4:grid:2", "grid:4:grid"}) {
    EXPECT_THROW(parse_anti_aliasing(bad), std::invalid_argument) << bad;
  }
  for (const char* text : {"none", "corners", "grid:3", "jitter:2", "adaptive:0.05:3", "refine:0.02:8",
                           "refine:0.5:16:grid"}) {
    EXPECT_EQ(to_string(parse_anti_aliasing(text)), text);
  }
  // Each range's ends are accepted (the values just past them are among the refusals above).
  EXPECT_EQ(parse_anti_aliasing("grid:1").n, 1);
  EXPECT_EQ(parse_anti_aliasing("grid:64").n, AntiAliasing::kMaxRaysPerSide);
  EXPECT_EQ(parse_anti_aliasing("jitter:64").n, AntiAliasing::kMaxRaysPerSide);
  EXPECT_EQ(parse_anti_aliasing("adaptive:0.1:0").depth, 0);
  EXPECT_EQ(parse_anti_aliasing("adaptive:0.1:6").depth, AntiAliasing::kMaxDepth);
  EXPECT_EQ(parse_anti_aliasing("refine:0.1:2").n, 2);
  EXPECT_EQ(parse_anti_aliasing("refine:0.1:16").n, AntiAliasing::kMaxRefineSide);
}

}  // namespace
}  // namespace quiver
