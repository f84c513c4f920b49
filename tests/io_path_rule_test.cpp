// The rule on files a scene names (io/path_rule.h): inside the scene's
// folder and below, symlinks resolved, unless allowed; and every reader
// that follows a name (OBJ mtllib and map_Kd, TOML meshes and images, glTF
// buffers and images, percent-encoded or not) refuses one outside before
// opening it, at the position that names it.
#include "io/path_rule.h"

#include <array>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "io/mesh_import.h"
#include "io/obj_reader.h"
#include "io/parse_error.h"
#include "io/scene_loader.h"
#include "io/toml_reader.h"
#include "tests/support/temporary_directory.h"

namespace quiver {
namespace {

namespace fs = std::filesystem;

void write_file(const fs::path& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

// A scene folder `scene/` beside a folder `private/` it must not reach.
class PathRuleTest : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(scene() / "sub");
    fs::create_directories(outside());
    write_file(outside() / "secret.mtl", "newmtl red\nKd 1 0 0\n");
    write_file(scene() / "sub" / "inside.mtl", "newmtl red\nKd 1 0 0\n");
    write_file(outside() / "mesh.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    fs::create_directory_symlink(outside(), scene() / "link");
  }
  fs::path scene() const { return dir_.path() / "scene"; }
  fs::path outside() const { return dir_.path() / "private"; }

  // The ParseError of loading `file` (in scene()) with the default rule.
  std::string load_error(const std::string& file) const {
    try {
      load_scene(scene() / file);
    } catch (const ParseError& error) {
      return error.what();
    }
    ADD_FAILURE() << "no ParseError for " << file;
    return {};
  }

  testing::TemporaryDirectory dir_{"quiver_path_rule_test"};
};

TEST_F(PathRuleTest, AdmitsTheFolderAndBelowOnly) {
  const PathRule rule = PathRule{}.for_folder(scene());
  EXPECT_TRUE(rule.admits(scene() / "a.png"));
  EXPECT_TRUE(rule.admits(scene() / "sub" / "missing.png"));
  EXPECT_TRUE(rule.admits(scene() / "sub" / ".." / "a.png"));
  EXPECT_FALSE(rule.admits(scene() / ".." / "private" / "secret.mtl"));
  EXPECT_FALSE(rule.admits("/etc/passwd"));
  EXPECT_FALSE(rule.admits(scene() / "link" / "secret.mtl"));  // a symlink out of the folder
  EXPECT_FALSE(rule.admits(scene()));                          // the folder itself is no file in it
  EXPECT_FALSE(rule.admits(dir_.path() / "scene2" / "a.png"));  // a sibling sharing the folder's name as prefix
  const PathRule allowed{true, {}};
  EXPECT_TRUE(allowed.for_folder(scene()).admits("/etc/passwd"));
  EXPECT_NE(rule.expected().find("--allow-outside-paths"), std::string::npos);
}

TEST_F(PathRuleTest, AnObjLibraryOrImageOutsideIsAnErrorAtItsName) {
  write_file(scene() / "up.obj", "mtllib ../private/secret.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string up = load_error("up.obj");
  EXPECT_NE(up.find("up.obj:1:8: in the MTL library named here"), std::string::npos) << up;
  EXPECT_NE(up.find("inside the scene's folder"), std::string::npos) << up;

  write_file(scene() / "sub" / "image.mtl", "newmtl red\nmap_Kd /etc/passwd\n");
  write_file(scene() / "image.obj", "mtllib sub/image.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n");
  const std::string image = load_error("image.obj");
  EXPECT_NE(image.find("image.mtl:2:8: expected a file inside the scene's folder"), std::string::npos) << image;
  EXPECT_EQ(image.find("root:"), std::string::npos) << "the file was read: " << image;

  write_file(scene() / "in.obj", "mtllib sub/inside.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n");
  EXPECT_EQ(load_scene(scene() / "in.obj").materials.at(0).color.x, 1.f);
  SceneLoadOptions allowed;
  allowed.allow_outside_paths = true;
  EXPECT_EQ(load_scene(scene() / "up.obj", allowed).triangles.size(), 1u);
}

TEST_F(PathRuleTest, ATomlMeshOrImageOutsideIsAnErrorAtItsKey) {
  write_file(scene() / "mesh.toml", "[[meshes]]\nfile = \"../private/mesh.obj\"\n");
  const std::string mesh = load_error("mesh.toml");
  EXPECT_NE(mesh.find("mesh.toml:2:8: expected a file inside the scene's folder"), std::string::npos) << mesh;
  write_file(scene() / "image.toml",
             "[[textures]]\nname = \"t\"\ntype = \"image\"\nfile = \"link/secret.mtl\"\n" + std::string(
                 "[[spheres]]\ncenter = [0, 0, 0]\nradius = 1\n"));
  const std::string image = load_error("image.toml");
  EXPECT_NE(image.find("image.toml:4:8: expected a file inside the scene's folder"), std::string::npos) << image;
  // A mesh inside may not reach out either: the rule is the scene's, not the mesh's folder's.
  write_file(scene() / "sub" / "up.obj", "mtllib ../../private/secret.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  write_file(scene() / "nested.toml", "[[meshes]]\nfile = \"sub/up.obj\"\n");
  EXPECT_NE(load_error("nested.toml").find("inside the scene's folder"), std::string::npos);
  SceneLoadOptions allowed;
  allowed.allow_outside_paths = true;
  EXPECT_EQ(load_scene(scene() / "mesh.toml", allowed).triangles.size(), 1u);
}

// triangle.gltf's geometry (tests/data/mesh) with its buffer in a file named `uri`.
std::string triangle_gltf(const std::string& buffer_uri, const std::string& image_uri = {}) {
  std::string json = R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
    "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1,
    "material": 0}]}], "materials": [{"pbrMetallicRoughness": {)";
  if (!image_uri.empty()) json += R"("baseColorTexture": {"index": 0})";
  json += "}}],";
  if (!image_uri.empty()) json += R"("textures": [{"source": 0}], "images": [{"uri": ")" + image_uri + R"("}],)";
  json += R"("buffers": [{"byteLength": 44, "uri": ")" + buffer_uri + R"("}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0],
    "max": [1, 1, 0]}, {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]})";
  return json;
}

std::string triangle_buffer() {
  const std::array<float, 9> positions{0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::array<std::uint16_t, 4> indices{0, 1, 2, 0};
  std::string bytes(44, '\0');
  std::memcpy(bytes.data(), positions.data(), 36);
  std::memcpy(bytes.data() + 36, indices.data(), 8);
  return bytes;
}

TEST_F(PathRuleTest, AGltfBufferOrImageOutsideIsAnErrorNamingTheGltf) {
  write_file(outside() / "data.bin", triangle_buffer());
  write_file(scene() / "data.bin", triangle_buffer());
  for (const std::string uri : {"../private/data.bin", "%2e%2e/private/data.bin", "link/data.bin"}) {
    SCOPED_TRACE(uri);
    write_file(scene() / "model.gltf", triangle_gltf(uri));
    const std::string message = load_error("model.gltf");
    EXPECT_EQ(message.rfind((scene() / "model.gltf").string() + ": expected buffers[0]'s file to be a file inside",
                            0),
              0u)
        << message;
  }
  write_file(scene() / "image.gltf", triangle_gltf("data.bin", "/etc/passwd"));
  const std::string image = load_error("image.gltf");
  EXPECT_NE(image.find("image.gltf: expected images[0]'s file to be a file inside"), std::string::npos) << image;
  EXPECT_EQ(image.find("root:"), std::string::npos) << "the file was read: " << image;

  write_file(scene() / "model.gltf", triangle_gltf("../private/data.bin"));
  SceneLoadOptions allowed;
  allowed.allow_outside_paths = true;
  EXPECT_EQ(load_scene(scene() / "model.gltf", allowed).triangles.size(), 1u);
  write_file(scene() / "model.gltf", triangle_gltf("data.bin"));
  EXPECT_EQ(load_scene(scene() / "model.gltf").triangles.size(), 1u);
}

}  // namespace
}  // namespace quiver
