#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/parse_error.h"
#include "io/scene_loader.h"
#include "tests/support/temporary_directory.h"

namespace quiver {
namespace {

namespace fs = std::filesystem;

const fs::path kTestData = fs::path(QUIVER_TEST_DATA_DIR);
const fs::path kExamples = kTestData / ".." / ".." / "io" / "examples";

std::size_t primitive_count(const SceneDesc& s) {
  return s.spheres.size() + s.planes.size() + s.triangles.size() + s.polygons.size() + s.cones.size();
}

TEST(SceneLoader, ChoosesTheReaderByExtensionIgnoringCase) {
  const testing::TemporaryDirectory temporary("quiver_loader_test");
  const fs::path& dir = temporary.path();
  // The same text is valid NFF only; the extension decides how it is read.
  const std::string nff = "f 1 0 0 1 0 0 0 1\ns 0 0 0 1\n";
  std::ofstream(dir / "a.NFF") << nff;
  std::ofstream(dir / "b.toml") << nff;
  std::ofstream(dir / "c.Obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  std::ofstream(dir / "d.txt") << nff;
  EXPECT_EQ(load_scene(dir / "a.NFF").spheres.size(), 1u);
  EXPECT_THROW(load_scene(dir / "b.toml"), ParseError);
  EXPECT_EQ(load_scene(dir / "c.Obj").triangles.size(), 1u);
  try {
    load_scene(dir / "d.txt");
    ADD_FAILURE() << "no ParseError";
  } catch (const ParseError& error) {
    EXPECT_EQ(error.line(), 0u);
    const std::string expected =
        "unknown scene format (extension '.txt'): expected .nff, .toml, .obj, .ply, .gltf, .glb or .stl";
    EXPECT_NE(std::string(error.what()).find(expected), std::string::npos)
        << error.what();
  }
}

// Every reader refuses a file without objects (issue 28), at its end.
TEST(SceneLoader, AnEmptySceneOfAnyFormatIsAnError) {
  const testing::TemporaryDirectory temporary("quiver_loader_test");
  for (const char* name : {"empty.nff", "empty.toml", "empty.obj"}) {
    const fs::path path = temporary.path() / name;
    std::ofstream{path};
    try {
      load_scene(path);
      ADD_FAILURE() << "no ParseError for " << name;
    } catch (const ParseError& error) {
      const std::string what = error.what();
      EXPECT_EQ(what.rfind(path.string() + ":1:1: expected at least one ", 0), 0u) << what;
      EXPECT_NE(what.find("found end of file with no objects"), std::string::npos) << what;
    }
  }
}

// An image read after the scene (load_scene reads textures last) that
// fails names the scene line that named it: TOML's file key, MTL's map_Kd.
TEST(SceneLoader, TextureErrorsPointAtTheTextThatNamesTheImage) {
  const testing::TemporaryDirectory temporary("quiver_loader_test");
  const fs::path& dir = temporary.path();
  const fs::path image = dir / "zeros.png";
  std::ofstream(image, std::ios::binary) << std::string(64, '\0');
  std::ofstream(dir / "scene.toml") << "[[textures]]\nname = \"t\"\ntype = \"image\"\nfile = \"zeros.png\"\n"
                                       "[[materials]]\nname = \"m\"\ntexture = \"t\"\n"
                                       "[[spheres]]\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"m\"\n";
  std::ofstream(dir / "mesh.obj") << "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n";
  std::ofstream(dir / "m.mtl") << "newmtl a\nKd 1 1 1\nmap_Kd -clamp on zeros.png\n";
  const std::string cause = image.string() + ": not an image: expected a PNG";
  const struct {
    fs::path scene, named_in;
    std::size_t line, column;
  } cases[] = {{dir / "scene.toml", dir / "scene.toml", 4, 8}, {dir / "mesh.obj", dir / "m.mtl", 3, 18}};
  for (const auto& c : cases) {
    try {
      load_scene(c.scene);
      ADD_FAILURE() << "no ParseError for " << c.scene;
    } catch (const ParseError& error) {
      EXPECT_EQ(fs::path(error.file()), c.named_in);
      EXPECT_EQ(error.line(), c.line);
      EXPECT_EQ(error.column(), c.column);
      const std::string prefix = c.named_in.string() + ":" + std::to_string(c.line) + ":" + std::to_string(c.column) +
                                 ": in the image texture named here: " + cause;
      EXPECT_EQ(std::string(error.what()).rfind(prefix, 0), 0u) << error.what();
    }
  }
}

// An included mesh's warnings are the scene's; strict loading refuses them
// at their place, in the mesh (and in a scene of its own alike).
TEST(SceneLoader, StrictReachesIncludedMeshesAndTheirWarningsReachTheScene) {
  const testing::TemporaryDirectory temporary("quiver_loader_test");
  const fs::path& dir = temporary.path();
  std::ofstream(dir / "mesh.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 # one face\n";
  std::ofstream(dir / "scene.toml") << "[[meshes]]\nfile = \"mesh.obj\"\n";
  for (const fs::path& scene : {dir / "scene.toml", dir / "mesh.obj"}) {
    SCOPED_TRACE(scene.string());
    const SceneDesc lenient = load_scene(scene);
    ASSERT_EQ(lenient.warnings.size(), 1u);
    EXPECT_EQ(lenient.warnings[0].rfind((dir / "mesh.obj").string() + ":4:9: warning: expected end of line", 0), 0u)
        << lenient.warnings[0];
    SceneLoadOptions strict;
    strict.strict = true;
    try {
      load_scene(scene, strict);
      ADD_FAILURE() << "no ParseError";
    } catch (const ParseError& error) {
      EXPECT_EQ(fs::path(error.file()), dir / "mesh.obj");
      EXPECT_EQ(error.line(), 4u);
      EXPECT_EQ(error.column(), 9u);
    }
  }
}

// Every example scene in io/examples loads and holds a camera, a light and geometry.
TEST(SceneLoader, EveryExampleSceneLoads) {
  std::vector<fs::path> examples;
  for (const fs::directory_entry& entry : fs::directory_iterator(kExamples)) {
    if (entry.path().extension() == ".toml") examples.push_back(entry.path());
  }
  std::sort(examples.begin(), examples.end());
  ASSERT_GE(examples.size(), 8u) << kExamples;
  for (const fs::path& example : examples) {
    SCOPED_TRACE(example.filename().string());
    SceneDesc scene;
    ASSERT_NO_THROW(scene = load_scene(example));
    EXPECT_TRUE(scene.camera.has_value());
    EXPECT_FALSE(scene.lights.empty());
    EXPECT_FALSE(scene.materials.empty());
    EXPECT_GT(primitive_count(scene), 0u);
  }
}

// source_files lists the scene, then each OBJ mesh and MTL library as read.
TEST(SceneLoader, RecordsEveryFileItReads) {
  const fs::path obj = kTestData / "obj" / "materials.obj";
  const SceneDesc from_obj = load_scene(obj);
  ASSERT_EQ(from_obj.source_files.size(), 2u);
  EXPECT_EQ(fs::path(from_obj.source_files[0]), obj);
  EXPECT_EQ(fs::path(from_obj.source_files[1]).filename(), "materials.mtl");
  EXPECT_TRUE(fs::equivalent(from_obj.source_files[1], kTestData / "obj" / "materials.mtl"));

  const fs::path toml = kExamples / "mesh_include.toml";
  const SceneDesc from_toml = load_scene(toml);
  ASSERT_EQ(from_toml.source_files.size(), 2u);
  EXPECT_EQ(fs::path(from_toml.source_files[0]), toml);
  EXPECT_TRUE(fs::equivalent(from_toml.source_files[1], kExamples / "octahedron.obj"));

  EXPECT_EQ(load_scene(kTestData / "scenes" / "tiny.nff").source_files,
            std::vector<std::string>{(kTestData / "scenes" / "tiny.nff").string()});
}

// roof.obj (two faces without normals, 30 degrees apart) alone and
// through a TOML mesh: smooth by default, faceted with the option at 0.
TEST(SceneLoader, TheCreaseAngleOptionReachesObjAndTomlMeshes) {
  const testing::TemporaryDirectory dir;
  const fs::path roof = kTestData / "obj" / "roof.obj";
  fs::copy_file(roof, dir.path() / "roof.obj");
  std::ofstream(dir.path() / "roof.toml") << "[[meshes]]\nfile = \"roof.obj\"\ncrease_angle = 10\n";
  const auto smoothed = [](const SceneDesc& scene) {
    return std::count_if(scene.triangles.begin(), scene.triangles.end(),
                         [](const SceneTriangle& t) { return t.triangle.normals.has_value(); });
  };
  EXPECT_EQ(smoothed(load_scene(roof)), 2);
  EXPECT_EQ(smoothed(load_scene(roof, {0.0})), 0);
  EXPECT_EQ(smoothed(load_scene(dir.path() / "roof.toml")), 0);  // its key: 10 degrees
  EXPECT_EQ(smoothed(load_scene(dir.path() / "roof.toml", {45.0})), 2);
  EXPECT_THROW(load_scene(roof, {-3.0}), std::invalid_argument);
}

}  // namespace
}  // namespace quiver
