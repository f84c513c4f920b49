// A command's scene build (app/scene_build.h): a bad description's error
// names the scene file it came from, or the built-in scene, before what
// the builder found; a good one builds.
#include "app/scene_build.h"

#include <cstdint>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

namespace quiver {
namespace {

SceneDesc sphere_with_material(std::uint32_t material) {
  SceneDesc desc;
  desc.camera = CameraDesc{{0.f, 0.f, 5.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 40.f, 0.f, 8, 8};
  desc.materials = {MaterialDesc{}};
  desc.spheres.push_back({{{0.f, 0.f, 0.f}, 1.f}, material});
  return desc;
}

std::string build_error(const SceneDesc& desc, const std::string& name) {
  try {
    build_named_scene(desc, {}, name);
  } catch (const std::runtime_error& error) {
    return error.what();
  }
  return "";
}

TEST(SceneBuild, ErrorsNameTheSceneOrTheBuiltInScene) {
  const SceneDesc bad = sphere_with_material(7);  // no material 7
  const std::string from_file = build_error(bad, "scenes/broken.nff");
  EXPECT_EQ(from_file.rfind("scenes/broken.nff: ", 0), 0u) << from_file;
  EXPECT_GT(from_file.size(), std::string("scenes/broken.nff: ").size()) << from_file;  // and what was wrong
  const std::string built_in = build_error(bad, "");
  EXPECT_EQ(built_in.rfind("the built-in scene: ", 0), 0u) << built_in;
  EXPECT_EQ(build_error(sphere_with_material(0), "scenes/good.nff"), "");
  EXPECT_EQ(build_named_scene(sphere_with_material(0), {}, "scenes/good.nff").primitive_count(), 1u);
}

}  // namespace
}  // namespace quiver
