// A glTF file's camera (io/gltf_camera.h): the first perspective camera
// depth-first from the scene's roots, placed by its node's world transform
// (TRS or matrix, through its ancestors), its yfov turned into quiver's
// angle over the longer side; orthographic cameras named, not used; bad
// values errors naming their JSON path.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "io/gltf_camera.h"
#include "io/mesh_import.h"
#include "io/parse_error.h"
#include "support/vec3_expect.h"

namespace quiver {
namespace {

GltfCamera read(const std::string& text) { return gltf_camera(nlohmann::json::parse(text), "t.gltf"); }

using testing::expect_vec3_near;

std::string error_of(const std::string& text) {
  try {
    read(text);
  } catch (const ParseError& error) {
    return error.what();
  }
  return "";
}

// A parent moved 5 along z holds a child turned a quarter about +y that
// holds the camera: the camera sits at (0, 0, 5) looking along -x (+y's
// quarter turn takes -z to -x), 2:1 wide, so 512 x 256, the angle over the
// longer side from yfov over the height.
TEST(GltfCamera, ThroughNestedTransformsWithTheAngleOverTheLongerSide) {
  const double s = std::sqrt(0.5);
  const std::string doc = R"({"scene": 0, "scenes": [{"nodes": [1]}], "nodes": [
      {"rotation": [0, )" + std::to_string(s) + ", 0, " + std::to_string(s) + R"(], "camera": 0},
      {"translation": [0, 0, 5], "children": [0]}],
    "cameras": [{"type": "perspective", "perspective": {"yfov": 0.5, "aspectRatio": 2.0, "znear": 0.1}}]})";
  const GltfCamera found = read(doc);
  ASSERT_TRUE(found.camera.has_value());
  const CameraDesc& c = *found.camera;
  expect_vec3_near(c.from, 0, 0, 5);
  expect_vec3_near(c.at - c.from, -1, 0, 0);
  expect_vec3_near(c.up, 0, 1, 0);
  EXPECT_EQ(c.width, 512);
  EXPECT_EQ(c.height, 256);
  EXPECT_NEAR(c.angle_degrees, 2.0 * std::atan(std::tan(0.25) * 511.0 / 256.0) * 180.0 / std::numbers::pi, 1e-4);
  EXPECT_TRUE(found.unused.empty());
}

// A "matrix" (column-major) places it; a tall aspect makes the image tall;
// no scenes: the roots are the nodes no other names.
TEST(GltfCamera, AMatrixAndATallAspect) {
  const std::string doc = R"({"nodes": [
      {"matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 2,3,4,1], "camera": 0}],
    "cameras": [{"type": "perspective", "perspective": {"yfov": 1.0, "aspectRatio": 0.5}}]})";
  const GltfCamera found = read(doc);
  ASSERT_TRUE(found.camera.has_value());
  expect_vec3_near(found.camera->from, 2, 3, 4);
  EXPECT_EQ(found.camera->width, 256);
  EXPECT_EQ(found.camera->height, 512);
  EXPECT_NEAR(found.camera->angle_degrees, 2.0 * std::atan(std::tan(0.5) * 511.0 / 512.0) * 180.0 / std::numbers::pi,
              1e-4);
}

// The first perspective camera in depth-first order wins; an orthographic
// one met first is named for a warning; none at all: no camera, no note.
TEST(GltfCamera, TheFirstPerspectiveCameraAndOrthographicOnesNamed) {
  const std::string cameras = R"("cameras": [{"type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1}},
      {"type": "perspective", "perspective": {"yfov": 0.7}}])";
  const GltfCamera found = read(R"({"scenes": [{"nodes": [0, 1]}], "nodes": [
      {"camera": 0, "children": [2]}, {"translation": [9, 9, 9], "camera": 1}, {"translation": [1, 0, 0], "camera": 1}],
      )" + cameras + "}");
  ASSERT_TRUE(found.camera.has_value());
  expect_vec3_near(found.camera->from, 1, 0, 0);  // node 2, below node 0, comes before node 1
  EXPECT_EQ(found.unused, "nodes[0] names cameras[0], of type orthographic; quiver's camera is a perspective one");
  // Without "scene", every scene's roots in turn (as gltf_check counts them).
  const GltfCamera second_scene = read(R"({"scenes": [{"nodes": [0]}, {"nodes": [1]}], "nodes": [
      {"translation": [1, 2, 3]}, {"translation": [4, 5, 6], "camera": 1}], )" + cameras + "}");
  ASSERT_TRUE(second_scene.camera.has_value());
  expect_vec3_near(second_scene.camera->from, 4, 5, 6);
  const GltfCamera none = read(R"({"nodes": [{"translation": [1, 2, 3]}]})");
  EXPECT_FALSE(none.camera.has_value());
  EXPECT_TRUE(none.unused.empty());
}

TEST(GltfCamera, BadValuesAreErrorsNamingTheirPath) {
  const std::string lens = R"("cameras": [{"type": "perspective", "perspective": {"yfov": 0.7}}])";
  EXPECT_EQ(error_of(R"({"nodes": [{"translation": [0, "x", 0], "camera": 0}], )" + lens + "}"),
            "t.gltf: expected nodes[0].translation to be an array of 3 finite numbers");
  EXPECT_EQ(error_of(R"({"nodes": [{"camera": 3}], )" + lens + "}"),
            "t.gltf: expected nodes[0].camera to be an index into cameras");
  EXPECT_EQ(error_of(R"({"nodes": [{"camera": 0}], "cameras": [{"type": "perspective", "perspective": {"yfov": 4}}]})"),
            "t.gltf: expected cameras[0].perspective.yfov to be a number of radians in (0, pi)");
  EXPECT_EQ(error_of(R"({"nodes": [{"scale": [0, 0, 0], "camera": 0}], )" + lens + "}"),
            "t.gltf: expected nodes[0] to be a transform that keeps a camera's view and up apart");
  // A yfov just below pi is a valid number, but its view across rounds to
  // 180 degrees in float: an error, as quiver's camera needs less.
  EXPECT_EQ(error_of(R"({"nodes": [{"camera": 0}], "cameras": [{"type": "perspective", )"
                     R"("perspective": {"yfov": 3.1415926535}}]})"),
            "t.gltf: expected cameras[0].perspective to be a view narrower than 180 degrees across");
}

// Assimp's own test file: a perspective camera at (0.5, 0.5, 3) looking
// down -z (and an orthographic one after it, not reached), read through
// the mesh importer into the scene.
TEST(GltfCamera, ThePublicCamerasFileGivesItsScene) {
  const char* env = std::getenv("QUIVER_ASSIMP_MODELS_DIR");
  const std::filesystem::path root = env != nullptr && *env != '\0' ? env : QUIVER_ASSIMP_MODELS_DIR;
  const std::filesystem::path file = root / "glTF2" / "cameras" / "Cameras.gltf";
  if (!std::filesystem::exists(file)) {
    GTEST_SKIP() << file << " not found: apt-get install assimp-testmodels, or set QUIVER_ASSIMP_MODELS_DIR";
  }
  const SceneDesc scene = read_imported_mesh(file);
  ASSERT_TRUE(scene.camera.has_value());
  expect_vec3_near(scene.camera->from, 0.5, 0.5, 3);
  expect_vec3_near(scene.camera->at - scene.camera->from, 0, 0, -1);
  EXPECT_TRUE(scene.warnings.empty());
}

}  // namespace
}  // namespace quiver
