#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <filesystem>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <stdexcept>
#include <utility>

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

// Points spread over the sphere (a Fibonacci lattice).
void expect_sphere_inside_image(const CameraDesc& c, int width, int height, const double center[3], double radius) {
  constexpr int kPoints = 2000;
  double min_x = 1e300, max_x = -1e300, min_y = 1e300, max_y = -1e300;
  for (int i = 0; i < kPoints; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / kPoints;
    const double ring = std::sqrt(1.0 - z * z);
    const double phi = i * std::numbers::pi * (3.0 - std::sqrt(5.0));
    const double p[3] = {center[0] + radius * ring * std::cos(phi), center[1] + radius * z,
                         center[2] + radius * ring * std::sin(phi)};
    double x = 0.0, y = 0.0;
    ASSERT_TRUE(project(c, width, height, p, x, y)) << "a point of the sphere is behind the camera";
    min_x = std::min(min_x, x);
    max_x = std::max(max_x, x);
    min_y = std::min(min_y, y);
    max_y = std::max(max_y, y);
  }
  EXPECT_GE(min_x, 0.0);
  EXPECT_LE(max_x, double(width));
  EXPECT_GE(min_y, 0.0);
  EXPECT_LE(max_y, double(height));
  // Framed, not lost in the middle: the sphere spans at least half the shorter side.
  EXPECT_GT(std::max(max_x - min_x, max_y - min_y), 0.5 * std::min(width, height));
}

TEST(AutoView, FramesTheBoundingSphereOfThePrimitives) {
  SceneDesc scene;
  scene.materials.emplace_back();
  scene.spheres.push_back({{{10.f, 2.f, -3.f}, 1.f}, 0});
  SceneTriangle triangle{};
  triangle.triangle.p = {Vec3<float>{14.f, 0.f, -5.f}, Vec3<float>{12.f, 6.f, -3.f}, Vec3<float>{10.f, 2.f, 1.f}};
  scene.triangles.push_back(triangle);
  scene.cones.push_back({{{8.f, 0.f, -3.f}, 0.5f, {8.f, 3.f, -3.f}, 0.25f}, 0});
  for (const auto& [width, height] : {std::pair{640, 480}, std::pair{300, 900}, std::pair{1, 1}}) {
    SceneDesc framed = scene;
    add_default_view(framed, width, height);
    ASSERT_TRUE(framed.camera.has_value());
    const CameraDesc& c = *framed.camera;
    EXPECT_EQ(c.width, width);
    EXPECT_EQ(c.height, height);
    EXPECT_EQ(c.angle_degrees, kDefaultViewAngleDegrees);
    // Bounding box x [7.5, 14] (cone rim to triangle), y [-0.5, 6] (cone
    // base rim to triangle), z [-5, 1] (triangle): its circumscribed sphere.
    const double center[3] = {10.75, 2.75, -2.0};
    const double radius = 0.5 * std::sqrt(6.5 * 6.5 + 6.5 * 6.5 + 6.0 * 6.0);
    if (width > 1) expect_sphere_inside_image(c, width, height, center, radius);
    // Front (+z), above (+y), to the right (+x) of the centre.
    EXPECT_GT(c.from.z, center[2]);
    EXPECT_GT(c.from.y, center[1]);
    EXPECT_GT(c.from.x, center[0]);
  }
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

TEST(AutoView, EmptySceneGetsASaneCameraAndALight) {
  SceneDesc scene;
  add_default_view(scene, 320, 240);
  ASSERT_TRUE(scene.camera.has_value());
  const double unit_center[3] = {0.0, 0.0, 0.0};
  expect_sphere_inside_image(*scene.camera, 320, 240, unit_center, 1.0);
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_EQ(scene.lights[0].kind, LightDesc::Kind::point);
  EXPECT_GT(scene.lights[0].color.x, 0.f);
  EXPECT_GT(scene.lights[0].position.y, scene.camera->from.y);  // above the eye
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

TEST(AutoView, KeepsWhatTheSceneHas) {
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
  add_default_view(scene, 640, 480);
  EXPECT_EQ(scene.camera->angle_degrees, 60.f);
  EXPECT_EQ(scene.camera->width, 10);
  ASSERT_EQ(scene.lights.size(), 1u);
  // Beside the scene's own camera, up and to its right (+x here).
  EXPECT_GT(scene.lights[0].position.x, 0.f);
  EXPECT_GT(scene.lights[0].position.y, 0.f);
  // A zero ambient becomes grey 0.1, every channel.
  EXPECT_EQ(scene.ambient.x, 0.1f);
  EXPECT_EQ(scene.ambient.y, 0.1f);
  EXPECT_EQ(scene.ambient.z, 0.1f);

  LightDesc light;
  light.position = {1.f, 2.f, 3.f};
  scene.lights = {light};
  add_default_view(scene, 640, 480);
  EXPECT_EQ(scene.lights.size(), 1u);
  EXPECT_THROW(add_default_view(scene, 0, 480), std::invalid_argument);
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
