#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <stdexcept>
#include <utility>
#include <vector>

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include "io/obj_reader.h"
#include "scene/auto_view.h"

namespace quiver {
namespace {

// Film position (pixels, origin top-left) of world point p under the
// CameraDesc convention: the angle spans the outermost pixel centres of the
// longer side; false when p is not in front of the camera.
bool project(const CameraDesc& c, int width, int height, const double p[3], double& x, double& y) {
  double f[3], r[3], u[3], d[3];
  for (int a = 0; a < 3; ++a) f[a] = double(c.at[a]) - double(c.from[a]);
  const double fl = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
  for (double& v : f) v /= fl;
  const double up[3] = {c.up.x, c.up.y, c.up.z};
  r[0] = f[1] * up[2] - f[2] * up[1];
  r[1] = f[2] * up[0] - f[0] * up[2];
  r[2] = f[0] * up[1] - f[1] * up[0];
  const double rl = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
  for (double& v : r) v /= rl;
  u[0] = r[1] * f[2] - r[2] * f[1];
  u[1] = r[2] * f[0] - r[0] * f[2];
  u[2] = r[0] * f[1] - r[1] * f[0];
  for (int a = 0; a < 3; ++a) d[a] = p[a] - double(c.from[a]);
  const double depth = d[0] * f[0] + d[1] * f[1] + d[2] * f[2];
  if (depth <= 0.0) return false;
  const double sx = (d[0] * r[0] + d[1] * r[1] + d[2] * r[2]) / depth;
  const double sy = (d[0] * u[0] + d[1] * u[1] + d[2] * u[2]) / depth;
  const double pixel = 2.0 * std::tan(double(c.angle_degrees) * std::numbers::pi / 360.0) /
                       double(std::max(std::max(width, height) - 1, 1));
  x = 0.5 * width + sx / pixel;
  y = 0.5 * height - sy / pixel;
  return true;
}

// Points spread over a sphere (a Fibonacci lattice).
std::vector<std::array<double, 3>> sphere_points(const double center[3], double radius) {
  constexpr int kPoints = 2000;
  std::vector<std::array<double, 3>> points;
  for (int i = 0; i < kPoints; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / kPoints;
    const double ring = std::sqrt(1.0 - z * z);
    const double phi = i * std::numbers::pi * (3.0 - std::sqrt(5.0));
    points.push_back({center[0] + radius * ring * std::cos(phi), center[1] + radius * z,
                      center[2] + radius * ring * std::sin(phi)});
  }
  return points;
}

// The film box (pixels) of the points' images; fails when one lies behind the camera.
struct FilmBox {
  double min_x = 1e300, max_x = -1e300, min_y = 1e300, max_y = -1e300;
};
FilmBox film_box(const CameraDesc& c, int width, int height, const std::vector<std::array<double, 3>>& points) {
  FilmBox box;
  for (const std::array<double, 3>& p : points) {
    double x = 0.0, y = 0.0;
    EXPECT_TRUE(project(c, width, height, p.data(), x, y)) << "a point is behind the camera";
    box.min_x = std::min(box.min_x, x);
    box.max_x = std::max(box.max_x, x);
    box.min_y = std::min(box.min_y, y);
    box.max_y = std::max(box.max_y, y);
  }
  return box;
}

void expect_inside_image(const FilmBox& box, int width, int height) {
  EXPECT_GE(box.min_x, 0.0);
  EXPECT_LE(box.max_x, double(width));
  EXPECT_GE(box.min_y, 0.0);
  EXPECT_LE(box.max_y, double(height));
}

void expect_sphere_inside_image(const CameraDesc& c, int width, int height, const double center[3], double radius) {
  const FilmBox box = film_box(c, width, height, sphere_points(center, radius));
  expect_inside_image(box, width, height);
  // Framed, not lost in the middle: the sphere spans at least half the shorter side.
  EXPECT_GT(std::max(box.max_x - box.min_x, box.max_y - box.min_y), 0.5 * std::min(width, height));
}

// The default camera frames a sphere, a triangle and a cone: every point of
// them is in the image, and the image of the sphere and the triangle (the
// cone counts by its bounding balls, which reach beyond it) is centred and
// spans kDefaultViewFill of the side it reaches first.
TEST(AutoView, FramesEveryPrimitiveCentredFillingTheImage) {
  SceneDesc scene;
  scene.materials.emplace_back();
  scene.spheres.push_back({{{10.f, 2.f, -3.f}, 1.f}, 0});
  SceneTriangle triangle{};
  triangle.triangle.p = {Vec3<float>{14.f, 0.f, -5.f}, Vec3<float>{12.f, 6.f, -3.f}, Vec3<float>{10.f, 2.f, 1.f}};
  scene.triangles.push_back(triangle);
  const double sphere_center[3] = {10.0, 2.0, -3.0};
  std::vector<std::array<double, 3>> exact = sphere_points(sphere_center, 1.0);
  for (const Vec3<float>& p : triangle.triangle.p) exact.push_back({p.x, p.y, p.z});
  SceneDesc with_cone = scene;
  with_cone.cones.push_back({{{8.f, 0.f, -3.f}, 0.5f, {8.f, 3.f, -3.f}, 0.25f}, 0});
  std::vector<std::array<double, 3>> rims = exact;
  for (int k = 0; k < 64; ++k) {
    const double a = 2.0 * std::numbers::pi * k / 64;
    rims.push_back({8.0 + 0.5 * std::cos(a), 0.0, -3.0 + 0.5 * std::sin(a)});
    rims.push_back({8.0 + 0.25 * std::cos(a), 3.0, -3.0 + 0.25 * std::sin(a)});
  }
  for (const auto& [width, height] : {std::pair{640, 480}, std::pair{300, 900}, std::pair{1, 1}}) {
    SCOPED_TRACE(std::to_string(width) + "x" + std::to_string(height));
    SceneDesc framed = scene, framed_with_cone = with_cone;
    add_default_view(framed, width, height);
    add_default_view(framed_with_cone, width, height);
    ASSERT_TRUE(framed.camera.has_value() && framed_with_cone.camera.has_value());
    const CameraDesc& c = *framed.camera;
    EXPECT_EQ(c.width, width);
    EXPECT_EQ(c.height, height);
    EXPECT_EQ(c.angle_degrees, kDefaultViewAngleDegrees);
    // Front (+z), above (+y), to the right (+x) of the model.
    EXPECT_GT(c.from.z, 1.f);
    EXPECT_GT(c.from.y, 6.f);
    EXPECT_GT(c.from.x, 14.f);
    if (width == 1) continue;
    expect_inside_image(film_box(*framed_with_cone.camera, width, height, rims), width, height);
    const FilmBox box = film_box(c, width, height, exact);
    expect_inside_image(box, width, height);
    // Pixel centres span width - 1 and height - 1; the fit is exact up to the centring's approximation.
    const double fill_x = (box.max_x - box.min_x) / double(width - 1);
    const double fill_y = (box.max_y - box.min_y) / double(height - 1);
    EXPECT_NEAR(std::max(fill_x, fill_y), kDefaultViewFill, 0.01);
    EXPECT_LE(std::max(fill_x, fill_y), kDefaultViewFill + 1e-6);
    EXPECT_NEAR(0.5 * (box.min_x + box.max_x), 0.5 * width, 0.01 * width);
    EXPECT_NEAR(0.5 * (box.min_y + box.max_y), 0.5 * height, 0.01 * height);
  }
}

// The view of a mesh large enough to be folded over threads in many blocks
// is the same bits on one thread as on every thread.
TEST(AutoView, AMeshFoldedOverThreadsGetsTheSameViewOnOneThread) {
  SceneDesc scene;
  scene.materials.emplace_back();
  std::uint32_t state = 12345;
  const auto next = [&] {  // a fixed LCG in [-1, 1), so the mesh is the same on every machine
    state = state * 1664525u + 1013904223u;
    return float(state >> 8) * 0x1p-23f - 1.f;
  };
  for (int t = 0; t < 60000; ++t) {
    SceneTriangle triangle{};
    for (Vec3<float>& p : triangle.triangle.p) p = {next() * 3.f, next(), next() * 2.f};
    scene.triangles.push_back(triangle);
  }
  const auto view_on = [&](std::size_t threads) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    SceneDesc framed = scene;
    add_default_view(framed, 640, 480);
    return *framed.camera;
  };
  const CameraDesc one = view_on(1), every = view_on(std::max<std::size_t>(2, tbb::this_task_arena::max_concurrency()));
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(std::bit_cast<std::uint32_t>(one.from[a]), std::bit_cast<std::uint32_t>(every.from[a])) << a;
    EXPECT_EQ(std::bit_cast<std::uint32_t>(one.at[a]), std::bit_cast<std::uint32_t>(every.at[a])) << a;
  }
}

// A mesh of many triangles is framed by its extreme vertices whatever the
// order of its triangles: stored ring by ring (each block of triangles a
// band around it) or shuffled, the default camera is the same to the bit,
// every vertex is in the image and the fit fills kDefaultViewFill.
TEST(AutoView, AMeshIsFramedByItsExtremeVerticesInAnyOrder) {
  constexpr int kRings = 120, kSegments = 240;
  const auto vertex = [](int i, int j) {
    const double theta = std::numbers::pi * i / kRings, phi = 2.0 * std::numbers::pi * j / kSegments;
    const double r = 1.0 + 0.05 * std::sin(7.0 * theta) * std::sin(5.0 * phi);
    return Vec3<float>{float(2.0 + r * std::sin(theta) * std::cos(phi)), float(r * std::cos(theta)),
                       float(-1.0 + 1.5 * r * std::sin(theta) * std::sin(phi))};
  };
  SceneDesc rings;
  rings.materials.emplace_back();
  std::vector<std::array<double, 3>> points;
  for (int i = 0; i < kRings; ++i) {
    for (int j = 0; j < kSegments; ++j) {
      const Vec3<float> a = vertex(i, j), b = vertex(i + 1, j), c = vertex(i + 1, j + 1), d = vertex(i, j + 1);
      for (const std::array<Vec3<float>, 3>& t : {std::array{a, b, c}, std::array{a, c, d}}) {
        SceneTriangle triangle{};
        triangle.triangle.p = t;
        rings.triangles.push_back(triangle);
      }
      points.push_back({a.x, a.y, a.z});
    }
  }
  SceneDesc shuffled = rings;
  std::uint32_t state = 7;
  for (std::size_t i = shuffled.triangles.size(); i > 1; --i) {  // Fisher-Yates with a fixed LCG
    state = state * 1664525u + 1013904223u;
    std::swap(shuffled.triangles[i - 1], shuffled.triangles[(state >> 8) % i]);
  }
  add_default_view(rings, 640, 480);
  add_default_view(shuffled, 640, 480);
  const CameraDesc& c = *rings.camera;
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(std::bit_cast<std::uint32_t>(c.from[a]), std::bit_cast<std::uint32_t>(shuffled.camera->from[a])) << a;
    EXPECT_EQ(std::bit_cast<std::uint32_t>(c.at[a]), std::bit_cast<std::uint32_t>(shuffled.camera->at[a])) << a;
  }
  const FilmBox box = film_box(c, 640, 480, points);
  expect_inside_image(box, 640, 480);
  const double fill = std::max((box.max_x - box.min_x) / 639.0, (box.max_y - box.min_y) / 479.0);
  EXPECT_NEAR(fill, kDefaultViewFill, 0.01);
  EXPECT_LE(fill, kDefaultViewFill + 1e-6);  // the farthest vertex sets the distance
}

// A different field of view frames the same way; a ball fills the shorter
// side, across or up, as its silhouette (not its centre) reaches it.
TEST(AutoView, FramesForTheAngleGiven) {
  SceneDesc scene;
  scene.materials.emplace_back();
  scene.spheres.push_back({{{0.f, 0.f, 0.f}, 2.f}, 0});
  for (const float angle : {10.f, 40.f, 120.f}) {
    for (const bool landscape : {true, false}) {
      const int width = landscape ? 200 : 100, height = landscape ? 100 : 200;
      SceneDesc framed = scene;
      add_default_camera(framed, width, height, std::nullopt, angle);
      ASSERT_TRUE(framed.camera.has_value());
      EXPECT_EQ(framed.camera->angle_degrees, angle);
      const double center[3] = {0.0, 0.0, 0.0};
      const FilmBox box = film_box(*framed.camera, width, height, sphere_points(center, 2.0));
      expect_inside_image(box, width, height);
      const double fill = landscape ? (box.max_y - box.min_y) / 99.0 : (box.max_x - box.min_x) / 99.0;
      EXPECT_NEAR(fill, kDefaultViewFill, 0.01) << angle << (landscape ? " landscape" : " portrait");
    }
  }
  SceneDesc refused = scene;
  EXPECT_THROW(add_default_camera(refused, 200, 100, std::nullopt, 180.f), std::invalid_argument);
  EXPECT_THROW(add_default_camera(refused, 200, 100, std::nullopt, 0.f), std::invalid_argument);
}

// An instance counts with the eight corners of its mesh's box, placed: a
// box-shaped mesh turned an eighth of a turn about x frames as the same
// triangles placed by hand do (its box's corners are its vertices).
TEST(AutoView, AnInstanceFramesAsItsPlacedTriangles) {
  const float lo[3] = {0.f, 0.f, 0.f}, hi[3] = {2.f, 1.f, 4.f};
  const auto corner = [&](int k) {
    return Vec3<float>{k & 1 ? hi[0] : lo[0], k & 2 ? hi[1] : lo[1], k & 4 ? hi[2] : lo[2]};
  };
  // Two triangles per face of the box, from its corner indices.
  const int faces[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
  SceneMesh box;
  for (const auto& f : faces) {
    for (const auto& tri : {std::array{f[0], f[1], f[2]}, std::array{f[0], f[2], f[3]}}) {
      SceneTriangle t{};
      t.triangle.p = {corner(tri[0]), corner(tri[1]), corner(tri[2])};
      box.triangles.push_back(t);
    }
  }
  const float c = std::sqrt(0.5f);
  AffineTransform turn{};  // an eighth of a turn about x, then a shift
  turn.m = {1.f, 0.f, 0.f, 3.f, 0.f, c, -c, -1.f, 0.f, c, c, 2.f};
  SceneDesc instanced;
  instanced.materials.emplace_back();
  instanced.meshes.push_back(box);
  instanced.instances.push_back({0, turn});
  SceneDesc placed;
  placed.materials.emplace_back();
  for (SceneTriangle t : box.triangles) {
    for (Vec3<float>& p : t.triangle.p) p = apply_point(turn, p);
    placed.triangles.push_back(t);
  }
  add_default_view(instanced, 320, 240);
  add_default_view(placed, 320, 240);
  ASSERT_TRUE(instanced.camera && placed.camera);
  const Vec3<float> a = instanced.camera->at, b = placed.camera->at;
  EXPECT_FLOAT_EQ(a.x, b.x);
  EXPECT_FLOAT_EQ(a.y, b.y);
  EXPECT_FLOAT_EQ(a.z, b.z);
  EXPECT_FLOAT_EQ(length(instanced.camera->from - a), length(placed.camera->from - b));
}

TEST(AutoView, ImageSidesUpToTheBound) {
  SceneDesc scene;
  scene.materials.emplace_back();
  scene.spheres.push_back({{{0.f, 0.f, 0.f}, 1.f}, 0});
  SceneDesc widest = scene;
  EXPECT_NO_THROW(add_default_view(widest, kMaxImageSide, kMaxImageSide));
  for (const auto& [width, height] : {std::pair{kMaxImageSide + 1, 1}, std::pair{1, kMaxImageSide + 1},
                                      std::pair{0, 1}, std::pair{1, 0}}) {
    SceneDesc refused = scene;
    EXPECT_THROW(add_default_view(refused, width, height), std::invalid_argument) << width << "x" << height;
  }
}

TEST(AutoView, EmptySceneGetsASaneCameraAndTheRig) {
  SceneDesc scene;
  add_default_view(scene, 320, 240);
  ASSERT_TRUE(scene.camera.has_value());
  const double unit_center[3] = {0.0, 0.0, 0.0};
  expect_sphere_inside_image(*scene.camera, 320, 240, unit_center, 1.0);
  ASSERT_EQ(scene.lights.size(), 2u);
  EXPECT_EQ(scene.lights[0].kind, LightDesc::Kind::point);
  EXPECT_GT(scene.lights[0].color.x, 0.f);
  EXPECT_GT(scene.lights[0].position.y, scene.camera->from.y);  // the key, above the eye
  EXPECT_EQ(scene.lights[1].position.x, scene.camera->from.x);  // the fill, at the eye
  ASSERT_TRUE(scene.background.has_value());
  EXPECT_EQ(scene.background->x, kDefaultRigBackground);
}

// A model spanning +-3.4e38 (the readers' largest coordinates): no camera in
// float frames it, and the error names the scene file rather than a camera
// that was never the user's.
TEST(AutoView, AModelTooLargeForAFloatCameraIsAnErrorNamingItsFile) {
  SceneDesc scene;
  scene.source_files = {"huge.obj"};
  for (const float x : {-3.4e38f, 3.4e38f}) {
    SceneTriangle t{};
    t.triangle.p = {Vec3<float>{x, 0.f, 0.f}, Vec3<float>{0.f, 1.f, 0.f}, Vec3<float>{0.f, 0.f, 1.f}};
    scene.triangles.push_back(t);
  }
  try {
    add_default_view(scene, 32, 32);
    FAIL() << "no error";
  } catch (const std::invalid_argument& error) {
    EXPECT_EQ(std::string(error.what()).rfind("huge.obj: expected a model that a default view can frame", 0), 0u)
        << error.what();
  }
  EXPECT_FALSE(scene.camera.has_value());
  scene.triangles.pop_back();
  scene.triangles[0].triangle.p[0].x = -1e37f;  // 1e37 across: framed, every camera coordinate finite
  add_default_view(scene, 32, 32);
  ASSERT_TRUE(scene.camera.has_value());
  for (int a = 0; a < 3; ++a) EXPECT_TRUE(std::isfinite(scene.camera->from[a]) && std::isfinite(scene.lights[0].position[a]));
}

// The rig follows the scene's camera: the key above and to its right, the
// fill at its eye, 70% and 30% of 1 minus the ambient; a zero ambient
// becomes 0.1 and a background of the scene's own stays.
// The rig's light in all is 1 less the largest ambient component, that
// component taken as at least 0.1 (a dim ambient does not brighten the
// lights past 0.9) and the total as at least 0.3.
TEST(AutoView, TheRigsLightIsOneLessTheLargestAmbientWithinItsFloors) {
  EXPECT_FLOAT_EQ(default_light_total({0.05f, 0.02f, 0.f}), 0.9f);
  EXPECT_FLOAT_EQ(default_light_total({0.1f, 0.1f, 0.1f}), 0.9f);
  EXPECT_FLOAT_EQ(default_light_total({0.2f, 0.5f, 0.1f}), 0.5f);
  EXPECT_FLOAT_EQ(default_light_total({0.9f, 0.f, 0.f}), 0.3f);
  // Through the rig: a dim, non-zero ambient is kept and the lights share 0.9.
  SceneDesc scene;
  scene.materials.emplace_back();
  scene.spheres.push_back({{{0.f, 0.f, 0.f}, 1.f}, 0});
  scene.ambient = {0.05f, 0.02f, 0.f};
  add_default_view(scene, 64, 48);
  ASSERT_EQ(scene.lights.size(), 2u);
  EXPECT_EQ(scene.ambient.x, 0.05f);
  EXPECT_FLOAT_EQ(scene.lights[0].color.x + scene.lights[1].color.x, 0.9f);
}

TEST(AutoView, KeepsWhatTheSceneHasAndLightsItsCamera) {
  SceneDesc scene;
  CameraDesc camera{};
  camera.from = {0.f, 0.f, 5.f};
  camera.at = {0.f, 0.f, 0.f};
  camera.up = {0.f, 1.f, 0.f};
  camera.angle_degrees = 60.f;
  camera.width = 10;
  camera.height = 10;
  scene.camera = camera;
  scene.ambient = {0.f, 0.f, 0.f};
  scene.background = Vec3<float>{0.f, 0.f, 0.f};
  add_default_view(scene, 640, 480);
  EXPECT_EQ(scene.camera->angle_degrees, 60.f);
  EXPECT_EQ(scene.camera->width, 10);
  ASSERT_EQ(scene.lights.size(), 2u);
  // The key: up and to the camera's right (+x here), half the view distance each way.
  EXPECT_FLOAT_EQ(scene.lights[0].position.x, 2.5f);
  EXPECT_FLOAT_EQ(scene.lights[0].position.y, 2.5f);
  EXPECT_FLOAT_EQ(scene.lights[0].position.z, 5.f);
  EXPECT_FLOAT_EQ(scene.lights[0].color.x, kDefaultKeyShare * 0.9f);
  // The fill: at the eye, the rest.
  EXPECT_EQ(scene.lights[1].position.x, 0.f);
  EXPECT_EQ(scene.lights[1].position.z, 5.f);
  EXPECT_FLOAT_EQ(scene.lights[1].color.x, (1.f - kDefaultKeyShare) * 0.9f);
  // A zero ambient becomes grey 0.1, every channel; the black background stays.
  EXPECT_EQ(scene.ambient.x, 0.1f);
  EXPECT_EQ(scene.ambient.y, 0.1f);
  EXPECT_EQ(scene.ambient.z, 0.1f);
  EXPECT_EQ(scene.background->x, 0.f);

  LightDesc light;
  light.position = {1.f, 2.f, 3.f};
  scene.lights = {light};
  EXPECT_FALSE(add_default_lights(scene));
  EXPECT_EQ(scene.lights.size(), 1u);
  EXPECT_THROW(add_default_view(scene, 0, 480), std::invalid_argument);
  SceneDesc no_camera;
  EXPECT_THROW(add_default_lights(no_camera), std::invalid_argument);
}

// A square of 2 n^2 triangles centred at c, spanning 2 h along axes a and b.
void add_square(SceneDesc& scene, const Vec3<float>& c, int a, int b, float h, int n) {
  if (scene.materials.empty()) scene.materials.emplace_back();
  const auto at = [&](int i, int j) {
    Vec3<float> p = c;
    p[a] += -h + 2.f * h * float(i) / float(n);
    p[b] += -h + 2.f * h * float(j) / float(n);
    return p;
  };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      SceneTriangle t{};
      t.triangle.p = {at(i, j), at(i + 1, j), at(i + 1, j + 1)};
      scene.triangles.push_back(t);
      t.triangle.p = {at(i, j), at(i + 1, j + 1), at(i, j + 1)};
      scene.triangles.push_back(t);
    }
  }
}

double box_centre(const SceneDesc& scene, int axis) {
  double lo = 1e300, hi = -1e300;
  for (const SceneTriangle& t : scene.triangles) {
    for (const Vec3<float>& p : t.triangle.p) {
      lo = std::min(lo, double(p[axis]));
      hi = std::max(hi, double(p[axis]));
    }
  }
  return 0.5 * (lo + hi);
}

TEST(AutoView, AMeshIsSeenFromTheSideItsTopLeansTo) {
  // A body (a floor square at y = 0) and a head above its -z end: a figure facing -z.
  SceneDesc figure;
  add_square(figure, {0.f, 0.f, 0.f}, 0, 2, 1.f, 6);
  add_square(figure, {0.f, 2.f, -0.75f}, 0, 2, 0.25f, 3);
  ASSERT_GE(figure.triangles.size(), kViewMeshTriangles);
  const DefaultView view = choose_default_view(figure);
  EXPECT_EQ(view.up.y, 1.0) << view.up_reason;
  EXPECT_EQ(view.front.z, -1.0) << view.front_reason;
  EXPECT_NE(view.front_reason.find("leans"), std::string::npos);
  SceneDesc framed = figure;
  const std::optional<DefaultView> added = add_default_view(framed, 320, 240);
  ASSERT_TRUE(added.has_value());
  const CameraDesc& c = *framed.camera;
  EXPECT_LT(c.from.z, box_centre(figure, 2));  // in front of the face
  EXPECT_GT(c.from.y, box_centre(figure, 1));  // above
  EXPECT_LT(c.from.x, box_centre(figure, 0));  // round to the figure's left (-x when facing -z)

  // The same head over the middle: no lean, the default front +z.
  SceneDesc upright;
  add_square(upright, {0.f, 0.f, 0.f}, 0, 2, 1.f, 6);
  add_square(upright, {0.f, 2.f, 0.f}, 0, 2, 0.25f, 3);
  const DefaultView straight = choose_default_view(upright);
  EXPECT_EQ(straight.front.z, 1.0) << straight.front_reason;

  // Exactly kViewMeshTriangles triangles are a mesh; one fewer are not.
  SceneDesc least;
  add_square(least, {0.f, 0.f, 0.f}, 0, 2, 1.f, 4);
  add_square(least, {0.f, 2.f, -0.75f}, 0, 2, 0.25f, 4);
  ASSERT_EQ(least.triangles.size(), kViewMeshTriangles);
  EXPECT_EQ(choose_default_view(least).front.z, -1.0);
  least.triangles.erase(least.triangles.begin());
  EXPECT_EQ(choose_default_view(least).front.z, 1.0);

  // Too few triangles to be a mesh (a hand-made scene): the default view.
  SceneDesc small;
  add_square(small, {0.f, 0.f, 0.f}, 0, 2, 1.f, 2);
  add_square(small, {0.f, 2.f, -0.75f}, 0, 2, 0.25f, 1);
  EXPECT_EQ(choose_default_view(small).front.z, 1.0);
}

// The shipped meshes (../shared/meshes): spot, the cow and the bunny face
// where their heads are (checked by eye on renders), so their default views
// show their faces; the teapot keeps the default front.
TEST(AutoView, TheSharedMeshesAreSeenFromTheirHeadsSide) {
  const char* env = std::getenv("QUIVER_SHARED_DIR");
  const std::filesystem::path meshes =
      std::filesystem::path(env != nullptr && *env != '\0' ? env : QUIVER_SHARED_DIR) / "meshes";
  if (!std::filesystem::is_directory(meshes)) {
    GTEST_SKIP() << "no " << meshes << ": set QUIVER_SHARED_DIR to the folder holding meshes/";
  }
  const std::pair<const char*, Vec3<double>> expected[] = {{"spot.obj", {0.0, 0.0, -1.0}},
                                                           {"cow.obj", {1.0, 0.0, 0.0}},
                                                           {"stanford-bunny.obj", {-1.0, 0.0, 0.0}},
                                                           {"teapot.obj", {0.0, 0.0, 1.0}}};
  for (const auto& [name, front] : expected) {
    const DefaultView view = choose_default_view(read_obj_scene(meshes / name));
    EXPECT_EQ(view.up.y, 1.0) << name << ": " << view.up_reason;
    EXPECT_EQ(view.front.x, front.x) << name << ": " << view.front_reason;
    EXPECT_EQ(view.front.z, front.z) << name << ": " << view.front_reason;
  }
}

// The up axis a format states wins over the shape, and --up over both.
TEST(AutoView, TheFormatsUpAxisPlacesTheViewUnlessUpIsGiven) {
  SceneDesc scene;
  scene.materials.emplace_back();
  scene.spheres.push_back({{{0.f, 0.f, 0.f}, 1.f}, 0});
  scene.model_up = SceneDesc::StatedUp{{0.f, 0.f, 1.f}, "STL's convention"};
  const DefaultView stated = choose_default_view(scene);
  EXPECT_EQ(stated.up.z, 1.0);
  EXPECT_EQ(stated.up_reason, "+z, STL's convention");
  EXPECT_EQ(stated.front.y, -1.0);  // +z's default front
  const DefaultView given = choose_default_view(scene, Vec3<double>{0.0, 1.0, 0.0});
  EXPECT_EQ(given.up.y, 1.0);
  EXPECT_EQ(given.up_reason, "+y, from --up");
  SceneDesc framed = scene;
  add_default_view(framed, 64, 64);
  ASSERT_TRUE(framed.camera.has_value());
  EXPECT_EQ(framed.camera->up.z, 1.f);
  EXPECT_GT(framed.camera->from.z, 0.f);  // 25 degrees above, along +z
}

TEST(AutoView, AMeshOnAFlatBaseAtItsLowestZStandsOnIt) {
  // A column along z: a base at z = 0, a top at z = 3, walls of x = +-1.
  SceneDesc column;
  add_square(column, {0.f, 0.f, 0.f}, 0, 1, 1.f, 4);
  add_square(column, {0.f, 0.f, 3.f}, 0, 1, 1.f, 4);
  add_square(column, {1.f, 0.f, 1.5f}, 1, 2, 1.f, 4);
  add_square(column, {-1.f, 0.f, 1.5f}, 1, 2, 1.f, 4);
  const DefaultView view = choose_default_view(column);
  EXPECT_EQ(view.up.z, 1.0) << view.up_reason;
  EXPECT_EQ(view.front.y, -1.0) << view.front_reason;  // +z's default front
  SceneDesc framed = column;
  add_default_view(framed, 320, 240);
  EXPECT_EQ(framed.camera->up.z, 1.f);
  EXPECT_GT(framed.camera->from.z, 1.5f);  // above, along z
  EXPECT_LT(framed.camera->from.y, 0.f);   // in front

  // A flat face at its lowest y as well: +y's convention stays.
  SceneDesc both = column;
  add_square(both, {0.f, -1.f, 1.5f}, 0, 2, 1.f, 4);
  EXPECT_EQ(choose_default_view(both).up.y, 1.0);
}

// The column of AMeshOnAFlatBaseAtItsLowestZStandsOnIt without its base: a top
// at z = 3 and walls of x = +-1 (y in [-1, 1], z in [0.5, 2.5]); no face of
// it lies within 1% of the extent of its lowest y or lowest z.
SceneDesc open_column() {
  SceneDesc column;
  add_square(column, {0.f, 0.f, 3.f}, 0, 1, 1.f, 4);
  add_square(column, {1.f, 0.f, 1.5f}, 1, 2, 1.f, 4);
  add_square(column, {-1.f, 0.f, 1.5f}, 1, 2, 1.f, 4);
  return column;
}

// The area of the triangles from `first` on, and of all of them.
std::pair<double, double> area_from(const SceneDesc& scene, std::size_t first) {
  double part = 0.0, total = 0.0;
  for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
    const auto& p = scene.triangles[i].triangle.p;
    const Vec3<double> a{p[0].x, p[0].y, p[0].z}, b{p[1].x, p[1].y, p[1].z}, c{p[2].x, p[2].y, p[2].z};
    const Vec3<double> n = cross(b - a, c - a);
    const double area = 0.5 * std::sqrt(dot(n, n));
    total += area;
    if (i >= first) part += area;
  }
  return {part, total};
}

// A base counts only within 1% of the z extent of the mesh's lowest point:
// under the column's flat base at z = 0, a downward spike (four faces to an
// apex below the base's centre) 0.5% of the column's height deep leaves the
// base within reach and the column stands on +z; one 3% deep puts the base
// out of reach (0.09 > 1% of 3.09), so up stays +y.
TEST(AutoView, ABaseCountsOnlyWithinAHundredthOfTheLowestZ) {
  for (const auto& [depth, stands] : {std::pair{0.005f * 3.f, true}, std::pair{0.03f * 3.f, false}}) {
    SceneDesc column = open_column();
    add_square(column, {0.f, 0.f, 0.f}, 0, 1, 1.f, 4);
    const Vec3<float> apex{0.f, 0.f, -depth}, corners[4] = {{-0.1f, -0.1f, 0.f}, {0.1f, -0.1f, 0.f},
                                                              {0.1f, 0.1f, 0.f}, {-0.1f, 0.1f, 0.f}};
    for (int k = 0; k < 4; ++k) {
      SceneTriangle t{};
      t.triangle.p = {corners[k], apex, corners[(k + 1) % 4]};
      column.triangles.push_back(t);
    }
    ASSERT_GE(column.triangles.size(), kViewMeshTriangles);
    const DefaultView view = choose_default_view(column);
    SCOPED_TRACE(::testing::Message() << "spike " << depth << " deep: " << view.up_reason);
    EXPECT_EQ(view.up.z, stands ? 1.0 : 0.0);
    EXPECT_EQ(view.up.y, stands ? 0.0 : 1.0);
  }
}

// A base is flat (faces within 2 degrees of facing along z), not only low:
// a floor of 64 teeth along x whose faces slope at 45 degrees, 1/64 high
// (every vertex within 1% of the column's height of the lowest z, the floor
// well over 2% of the area), is no base and up stays +y; the same floor
// flat stands on +z.
TEST(AutoView, ALowFloorOfSteepFacesIsNoBase) {
  constexpr int kTeeth = 64;
  for (const bool ridged : {true, false}) {
    SceneDesc column = open_column();
    const std::size_t floor_from = column.triangles.size();
    const float width = 2.f / kTeeth, rise = ridged ? 0.5f * width : 0.f;  // 45 degrees when ridged
    ASSERT_LE(rise, 0.01f * 3.f);
    for (int k = 0; k < kTeeth; ++k) {
      const float x0 = -1.f + width * float(k), xs[3] = {x0, x0 + 0.5f * width, x0 + width};
      const float zs[3] = {0.f, rise, 0.f};
      for (int face = 0; face < 2; ++face) {
        const Vec3<float> near0{xs[face], -1.f, zs[face]}, near1{xs[face + 1], -1.f, zs[face + 1]};
        const Vec3<float> far0{xs[face], 1.f, zs[face]}, far1{xs[face + 1], 1.f, zs[face + 1]};
        SceneTriangle t{};
        t.triangle.p = {near0, near1, far1};
        column.triangles.push_back(t);
        t.triangle.p = {near0, far1, far0};
        column.triangles.push_back(t);
      }
    }
    const auto [floor_area, total_area] = area_from(column, floor_from);
    ASSERT_GE(floor_area, 0.02 * total_area);
    const DefaultView view = choose_default_view(column);
    SCOPED_TRACE(::testing::Message() << (ridged ? "ridged" : "flat") << " floor: " << view.up_reason);
    EXPECT_EQ(view.up.z, ridged ? 0.0 : 1.0);
    EXPECT_EQ(view.up.y, ridged ? 1.0 : 0.0);
  }
}

TEST(AutoView, AGivenUpAxisPlacesTheView) {
  SceneDesc scene;
  add_square(scene, {0.f, 0.f, 0.f}, 1, 2, 1.f, 6);
  const std::optional<DefaultView> view = add_default_view(scene, 320, 240, Vec3<double>{2.0, 0.0, 0.0});
  ASSERT_TRUE(view.has_value());
  EXPECT_EQ(view->up.x, 1.0);
  EXPECT_NE(view->up_reason.find("--up"), std::string::npos);
  EXPECT_EQ(scene.camera->up.x, 1.f);
  EXPECT_GT(scene.camera->from.x, 0.f);  // above along +x
  EXPECT_THROW(add_default_view(scene, 320, 240, Vec3<double>{0.0, 0.0, 0.0}), std::invalid_argument);
  // A scene with a camera keeps it and reports no view.
  EXPECT_FALSE(add_default_view(scene, 320, 240).has_value());
}

}  // namespace
}  // namespace quiver
