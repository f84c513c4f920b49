// A glTF file's punctual lights (io/gltf_lights.h): placed by their nodes'
// world transforms, scaled by their illuminance at the model's centre
// against each other to the default rig's total, spots and ranges named
// (an error with --strict), bad values errors naming their JSON path; read
// through the mesh importer, they replace the default rig.
#include <cmath>
#include <numbers>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include <gtest/gtest.h>

#include "io/gltf_lights.h"
#include "io/mesh_import.h"
#include "io/parse_error.h"
#include "scene/auto_view.h"
#include "support/vec3_expect.h"

namespace quiver {
namespace {

GltfLights read(const std::string& text) { return gltf_lights(nlohmann::json::parse(text), "t.gltf"); }

using testing::expect_vec3_near;

std::string error_of(const std::string& text) {
  try {
    read(text);
  } catch (const ParseError& error) {
    return error.what();
  }
  return "";
}

std::string with_lights(const std::string& lights, const std::string& nodes) {
  return R"({"extensions": {"KHR_lights_punctual": {"lights": )" + lights + R"(}}, "nodes": )" + nodes + "}";
}

std::string names_light(int index, const std::string& rest = "") {
  return R"({"extensions": {"KHR_lights_punctual": {"light": )" + std::to_string(index) + "}}" + rest + "}";
}

// A point light under a parent moved along z and scaled by 2: at (2, 4, 6 + 1);
// a directional light turned a quarter about +x shines along +y (the turn
// takes -z to +y); colours and intensities as given, defaults where absent.
TEST(GltfLights, PlacedByTheirNodes) {
  const double s = std::sqrt(0.5);
  const std::string doc = with_lights(
      R"([{"type": "point", "color": [1, 0.5, 0.25], "intensity": 40},
          {"type": "directional"}])",
      "[" + names_light(0, R"(, "translation": [1, 2, 3])") + R"(,
        {"translation": [0, 0, 1], "scale": [2, 2, 2], "children": [0]},)" +
          names_light(1, R"(, "rotation": [)" + std::to_string(s) + ", 0, 0, " + std::to_string(s) + "]") + "]");
  const GltfLights found = read(doc);
  ASSERT_EQ(found.lights.size(), 2u);
  // Depth-first from the roots (nodes 1 and 2, no node names 1 or 2): node 0 under node 1, then node 2.
  EXPECT_EQ(found.lights[0].light.kind, LightDesc::Kind::point);
  expect_vec3_near(found.lights[0].light.position, 2, 4, 7);
  expect_vec3_near(found.lights[0].light.color, 1, 0.5, 0.25);
  EXPECT_EQ(found.lights[0].intensity, 40.0);
  EXPECT_EQ(found.lights[1].light.kind, LightDesc::Kind::directional);
  expect_vec3_near(found.lights[1].light.direction, 0, 1, 0);
  expect_vec3_near(found.lights[1].light.color, 1, 1, 1);
  EXPECT_EQ(found.lights[1].intensity, 1.0);
  EXPECT_TRUE(found.ranges.empty());
}

// 100 cd at 10 from the centre is 1 lux there; a directional light of 3 lux
// in (1, 0.5, 0.5): brightest channels 1 + 3 = 4 share the rig's 0.9.
TEST(GltfLights, ScaledByTheirIlluminanceAtTheCentre) {
  GltfLights lights;
  GltfLight point;
  point.light.kind = LightDesc::Kind::point;
  point.light.position = {1.f, 10.f, 0.f};
  point.intensity = 100.0;
  GltfLight sun;
  sun.light.kind = LightDesc::Kind::directional;
  sun.light.color = {1.f, 0.5f, 0.5f};
  sun.intensity = 3.0;
  lights.lights = {point, sun};
  const Vec3<float> ambient{0.1f, 0.1f, 0.1f};
  ASSERT_FLOAT_EQ(default_light_total(ambient), 0.9f);
  const std::vector<LightDesc> scaled = scaled_gltf_lights(lights, {1.f, 0.f, 0.f}, ambient);
  ASSERT_EQ(scaled.size(), 2u);
  expect_vec3_near(scaled[0].color, 0.225, 0.225, 0.225);
  expect_vec3_near(scaled[0].position, 1, 10, 0);
  expect_vec3_near(scaled[1].color, 0.675, 0.3375, 0.3375);
  // A larger ambient leaves less to the lights, as for the rig.
  EXPECT_NEAR(scaled_gltf_lights(lights, {1.f, 0.f, 0.f}, {0.5f, 0.2f, 0.2f})[0].color.x, 0.5 / 4.0, 1e-6);
  // The lights' largest components sum to the total: a dimmer colour takes less of it.
  lights.lights[1].light.color = {0.5f, 0.25f, 0.25f};
  const std::vector<LightDesc> dimmer = scaled_gltf_lights(lights, {1.f, 0.f, 0.f}, ambient);
  expect_vec3_near(dimmer[0].color, 0.36, 0.36, 0.36);  // 0.9 / (1 + 3 x 0.5)
  expect_vec3_near(dimmer[1].color, 0.54, 0.27, 0.27);
  // Dark lights stay dark.
  lights.lights[0].intensity = 0.0;
  lights.lights[1].intensity = 0.0;
  for (const LightDesc& l : scaled_gltf_lights(lights, {0.f, 0.f, 0.f}, ambient)) expect_vec3_near(l.color, 0, 0, 0);
}

// A spot is placed as a point light with a direction and its cone; a light
// with a range is named.
TEST(GltfLights, SpotsKeepTheirConeAndRangesAreNamed) {
  const GltfLights found = read(with_lights(
      R"([{"type": "spot", "spot": {"innerConeAngle": 0.25, "outerConeAngle": 0.5}}, {"type": "point", "range": 4}])",
      "[" + names_light(0, R"(, "translation": [0, 3, 0])") + "," + names_light(1) + "]"));
  ASSERT_EQ(found.lights.size(), 2u);
  const LightDesc& spot = found.lights[0].light;
  EXPECT_EQ(spot.kind, LightDesc::Kind::spot);
  expect_vec3_near(spot.position, 0, 3, 0);
  expect_vec3_near(spot.direction, 0, 0, -1);
  EXPECT_FLOAT_EQ(spot.cone_inner_cos, float(std::cos(0.25)));
  EXPECT_FLOAT_EQ(spot.cone_outer_cos, float(std::cos(0.5)));
  EXPECT_EQ(found.lights[1].light.kind, LightDesc::Kind::point);
  ASSERT_EQ(found.ranges.size(), 1u);
  EXPECT_EQ(found.ranges[0], "nodes[1] names extensions.KHR_lights_punctual.lights[1]");
  // glTF's default cone: 0 to pi/4.
  const GltfLights plain = read(with_lights(R"([{"type": "spot", "spot": {}}])", "[" + names_light(0) + "]"));
  EXPECT_FLOAT_EQ(plain.lights[0].light.cone_inner_cos, 1.f);
  EXPECT_FLOAT_EQ(plain.lights[0].light.cone_outer_cos, float(std::cos(std::numbers::pi / 4)));
  // The widest cone glTF allows, pi/2 (as JSON writes the double), is kept.
  const GltfLights widest = read(with_lights(R"([{"type": "spot", "spot": {"outerConeAngle": 1.5707963267948966}}])",
                                             "[" + names_light(0) + "]"));
  ASSERT_EQ(widest.lights.size(), 1u);
  EXPECT_FLOAT_EQ(widest.lights[0].light.cone_outer_cos, float(std::cos(std::numbers::pi / 2)));
}

TEST(GltfLights, BadValuesNameTheirPath) {
  const std::string node = "[" + names_light(0) + "]";
  EXPECT_EQ(error_of(with_lights(R"([{"type": "area"}])", node)),
            "t.gltf: expected extensions.KHR_lights_punctual.lights[0].type to be \"point\", \"spot\" or "
            "\"directional\"");
  EXPECT_EQ(error_of(with_lights(R"([{"type": "point", "color": [1, 2, 0]}])", node)),
            "t.gltf: expected extensions.KHR_lights_punctual.lights[0].color to be an array of three numbers in "
            "[0, 1]");
  EXPECT_EQ(error_of(with_lights(R"([{"type": "spot", "spot": {"innerConeAngle": 0.5, "outerConeAngle": 0.5}}])", node)),
            "t.gltf: expected extensions.KHR_lights_punctual.lights[0].spot to be an object whose innerConeAngle "
            "(default 0) and outerConeAngle (default pi/4) satisfy 0 <= inner < outer <= pi/2");
  EXPECT_NE(error_of(with_lights(R"([{"type": "spot"}])", node)), "");
  EXPECT_EQ(error_of(with_lights(R"([{"type": "point", "intensity": -1}])", node)),
            "t.gltf: expected extensions.KHR_lights_punctual.lights[0].intensity to be a finite number >= 0");
  EXPECT_EQ(error_of(with_lights(R"([{"type": "point"}])", "[" + names_light(1) + "]")),
            "t.gltf: expected nodes[0].extensions.KHR_lights_punctual.light to be an index into the file's "
            "KHR_lights_punctual lights");
  EXPECT_EQ(error_of(R"({"nodes": [)" + names_light(0) + "]}"),
            "t.gltf: expected nodes[0].extensions.KHR_lights_punctual.light to be an index into the file's "
            "KHR_lights_punctual lights");
  EXPECT_EQ(error_of(with_lights(R"([{"type": "directional"}])", "[" + names_light(0, R"(, "scale": [1, 1, 0])") + "]")),
            "t.gltf: expected nodes[0] to be a transform that keeps a light's direction");
  // No lights and no nodes naming any: nothing, no error.
  EXPECT_TRUE(read(R"({"nodes": [{}]})").lights.empty());
}

// The test triangle with a point light and a spot with a range
// (tests/data/mesh/lit.gltf): the scene keeps them (no default rig), on the
// rig's grey, the range named in a warning; --strict refuses it.
TEST(GltfLights, ReadThroughTheImporterInsteadOfTheRig) {
  const std::filesystem::path file = std::filesystem::path(QUIVER_TEST_DATA_DIR) / "mesh" / "lit.gltf";
  const SceneDesc scene = read_imported_mesh(file);
  ASSERT_EQ(scene.lights.size(), 2u);
  EXPECT_EQ(scene.lights[0].kind, LightDesc::Kind::point);
  expect_vec3_near(scene.lights[0].position, 0, 0, 5);
  EXPECT_EQ(scene.lights[1].kind, LightDesc::Kind::spot);
  expect_vec3_near(scene.lights[1].position, 0, 5, 2);
  expect_vec3_near(scene.lights[1].direction, 0, -1, 0);  // turned a quarter about -x: -z to -y
  ASSERT_TRUE(scene.background.has_value());
  expect_vec3_near(*scene.background, kDefaultRigBackground, kDefaultRigBackground, kDefaultRigBackground);
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_NE(scene.warnings[0].find("nodes[2] names extensions.KHR_lights_punctual.lights[1], with a range"),
            std::string::npos)
      << scene.warnings[0];
  EXPECT_THROW(read_imported_mesh(file, 60.0, true), ParseError);
}

}  // namespace
}  // namespace quiver
