// glTF's node trees walked depth-first with world transforms
// (io/gltf_node_walk.h): translation x rotation x scale through the
// ancestors, each quaternion axis turning the way glTF's right-handed
// rotations do, a "matrix" column-major; the walk stops when asked.
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/gltf_node_walk.h"
#include "support/vec3_expect.h"

namespace quiver {
namespace {

struct Visit {
  std::string path;
  GltfMatrix world;
};

std::vector<Visit> walk(const std::string& text, std::size_t stop_after = 1000) {
  std::vector<Visit> seen;
  walk_gltf_nodes(nlohmann::json::parse(text), "t.gltf",
                  [&](const nlohmann::json&, const std::string& path, const GltfMatrix& world) {
                    seen.push_back({path, world});
                    return seen.size() < stop_after;
                  });
  return seen;
}

using testing::expect_vec3_near;

// glTF's quaternion (x, y, z, w) of a quarter turn about an axis.
std::string quarter_turn_about(int axis) {
  const std::string s = std::to_string(std::sqrt(0.5));  // six decimals: unit to 1e-6
  return "[" + (axis == 0 ? s : "0") + ", " + (axis == 1 ? s : "0") + ", " + (axis == 2 ? s : "0") + ", " + s + "]";
}

// A quarter turn about each axis takes the next axis to the one after it
// (x: y to z, y: z to x, z: x to y), as a right-handed rotation does.
TEST(GltfNodeWalk, QuarterTurnsAboutEachAxisAreRightHanded) {
  for (int axis = 0; axis < 3; ++axis) {
    const std::vector<Visit> seen = walk(R"({"nodes": [{"rotation": )" + quarter_turn_about(axis) + "}]}");
    ASSERT_EQ(seen.size(), 1u);
    const int next = (axis + 1) % 3, after = (axis + 2) % 3;
    const double in[3] = {next == 0 ? 1.0 : 0.0, next == 1 ? 1.0 : 0.0, next == 2 ? 1.0 : 0.0};
    const Vec3<float> turned = gltf_transformed(seen[0].world, in[0], in[1], in[2], 0);
    EXPECT_NEAR(turned[after], 1.0, 1e-5) << "axis " << axis;
    EXPECT_NEAR(turned[next], 0.0, 1e-5) << "axis " << axis;
    EXPECT_NEAR(turned[axis], 0.0, 1e-5) << "axis " << axis;
  }
}

// A child's world transform is its parent's times its own: a point at the
// child's (1, 0, 0) under a parent turned a quarter about z, scaled by 2 and
// moved by (5, 0, 0) lands at (5, 2, 0); a matrix places it column-major.
TEST(GltfNodeWalk, ChildrenComposeWithTheirParentsDepthFirst) {
  const std::vector<Visit> seen = walk(
      R"({"scene": 0, "scenes": [{"nodes": [1, 2]}], "nodes": [
        {"translation": [1, 0, 0]},
        {"translation": [5, 0, 0], "rotation": )" +
      quarter_turn_about(2) + R"(, "scale": [2, 2, 2], "children": [0]},
        {"matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 7,8,9,1]}]})");
  ASSERT_EQ(seen.size(), 3u);
  EXPECT_EQ(seen[0].path, "nodes[1]");
  EXPECT_EQ(seen[1].path, "nodes[0]");
  EXPECT_EQ(seen[2].path, "nodes[2]");
  expect_vec3_near(gltf_transformed(seen[1].world, 0, 0, 0, 1), 5, 2, 0);
  expect_vec3_near(gltf_transformed(seen[1].world, 1, 0, 0, 0), 0, 2, 0);  // a direction: no translation
  expect_vec3_near(gltf_transformed(seen[2].world, 1, 1, 1, 1), 8, 9, 10);
  // Stopped after the first node: the rest are not visited.
  EXPECT_EQ(walk(R"({"nodes": [{}, {}, {}]})", 1).size(), 1u);
}

TEST(GltfNodeWalk, NonFiniteTransformsAreErrorsNamingTheirPath) {
  try {
    walk(R"({"nodes": [{"scale": [1, 1]}]})");
    FAIL() << "no error";
  } catch (const ParseError& error) {
    EXPECT_STREQ(error.what(), "t.gltf: expected nodes[0].scale to be an array of 3 finite numbers");
  }
}

}  // namespace
}  // namespace quiver
