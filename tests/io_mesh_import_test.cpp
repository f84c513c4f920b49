// Tests of io/mesh_import.h (PLY through io/ply_reader.h, glTF 2.0 and STL
// through the quiver_assimp module), io/mesh_file_check.h (the bounds
// checked before Assimp reads a file) and io/mesh_append.h (a mesh of any
// format under a transform).
#include <sys/mman.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdlib>
#include <cstdint>
#include <limits>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "io/mesh_append.h"
#include "io/mesh_file_check.h"
#include "io/mesh_import.h"
#include "io/obj_reader.h"
#include "io/parse_error.h"
#include "io/scene_loader.h"
#include "io/texture_image.h"
#include "tests/support/base64.h"
#include "tests/support/gltf_text.h"
#include "tests/support/temporary_directory.h"

namespace quiver {
namespace {

namespace fs = std::filesystem;

const fs::path kMeshes = fs::path(QUIVER_TEST_DATA_DIR) / "mesh";
const fs::path kObj = fs::path(QUIVER_TEST_DATA_DIR) / "obj";

void write_file(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

std::string file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

using testing::base64_decoded;

template <typename T>
void put(std::string& bytes, T value, bool big_endian = false) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  if (big_endian) std::reverse(raw, raw + sizeof(T));
  bytes.append(raw, sizeof(T));
}

// The roof (tests/data/obj/roof.obj) as a binary PLY of the OBJ reader's
// float positions, in either byte order.
std::string binary_roof_ply(const SceneDesc& obj, bool big_endian) {
  std::string bytes = std::string("ply\nformat ") + (big_endian ? "binary_big_endian" : "binary_little_endian") +
                      " 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                      "element face 2\nproperty list uchar int vertex_indices\nend_header\n";
  // roof.obj's faces are 1 3 2 and 1 2 4: vertex k is the first corner that names it.
  const std::array<Vec3<float>, 4> v{obj.triangles[0].triangle.p[0], obj.triangles[0].triangle.p[2],
                                     obj.triangles[0].triangle.p[1], obj.triangles[1].triangle.p[2]};
  for (const Vec3<float>& p : v) {
    put(bytes, p.x, big_endian);
    put(bytes, p.y, big_endian);
    put(bytes, p.z, big_endian);
  }
  for (const std::array<std::int32_t, 3>& face : {std::array<std::int32_t, 3>{0, 2, 1}, {0, 1, 3}}) {
    put<std::uint8_t>(bytes, 3);
    for (std::int32_t index : face) put(bytes, index, big_endian);
  }
  return bytes;
}

// The roof as a binary STL whose facet normals are all +x (wrong on purpose:
// STL's normals are not used).
std::string binary_roof_stl(const SceneDesc& obj) {
  std::string bytes(80, ' ');
  put<std::uint32_t>(bytes, 2);
  for (const SceneTriangle& t : obj.triangles) {
    for (float n : {1.f, 0.f, 0.f}) put(bytes, n);
    for (const Vec3<float>& p : t.triangle.p) {
      put(bytes, p.x);
      put(bytes, p.y);
      put(bytes, p.z);
    }
    put<std::uint16_t>(bytes, 0);
  }
  return bytes;
}

void expect_same_triangles(const SceneDesc& a, const SceneDesc& b, float tolerance) {
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  for (std::size_t t = 0; t < a.triangles.size(); ++t) {
    const TriangleDesc& x = a.triangles[t].triangle;
    const TriangleDesc& y = b.triangles[t].triangle;
    ASSERT_EQ(x.normals.has_value(), y.normals.has_value()) << "triangle " << t;
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_NEAR(x.p[k].x, y.p[k].x, tolerance) << t << "," << k;
      EXPECT_NEAR(x.p[k].y, y.p[k].y, tolerance) << t << "," << k;
      EXPECT_NEAR(x.p[k].z, y.p[k].z, tolerance) << t << "," << k;
      if (!x.normals) continue;
      EXPECT_NEAR((*x.normals)[k].x, (*y.normals)[k].x, tolerance) << t << "," << k;
      EXPECT_NEAR((*x.normals)[k].y, (*y.normals)[k].y, tolerance) << t << "," << k;
      EXPECT_NEAR((*x.normals)[k].z, (*y.normals)[k].z, tolerance) << t << "," << k;
    }
  }
}

// What read_imported_mesh throws for path, or "" when it reads it.
std::string import_error(const fs::path& path) {
  try {
    read_imported_mesh(path);
  } catch (const ParseError& error) {
    return error.what();
  }
  return "";
}

TEST(MeshImport, AsciiPlyIsTheSameRoofAsTheObjWithTheSameSmoothNormals) {
  const SceneDesc obj = read_obj_scene(kObj / "roof.obj");
  const SceneDesc ply = read_imported_mesh(kMeshes / "roof.ply");
  ASSERT_TRUE(obj.triangles[0].triangle.normals.has_value());  // 30 degrees apart: smooth at the default 60
  // Assimp's decimal parser is not correctly rounded: the last bit may differ.
  expect_same_triangles(obj, ply, 1e-6f);
  ASSERT_EQ(ply.materials.size(), 1u);
  EXPECT_EQ(ply.materials[0].color.x, MaterialDesc{}.color.x);
  EXPECT_TRUE(ply.warnings.empty());
  // The crease angle applies as to OBJ: below 30 degrees, faceted.
  const SceneDesc faceted = read_imported_mesh(kMeshes / "roof.ply", 20.0);
  EXPECT_FALSE(faceted.triangles[0].triangle.normals.has_value());
}

TEST(MeshImport, BinaryPlyInEitherByteOrderAndBinaryStlMatchTheObjExactly) {
  const testing::TemporaryDirectory temporary("quiver_mesh_test");
  const SceneDesc obj = read_obj_scene(kObj / "roof.obj");
  for (bool big_endian : {false, true}) {
    const fs::path path = temporary.path() / (big_endian ? "big.ply" : "little.ply");
    write_file(path, binary_roof_ply(obj, big_endian));
    expect_same_triangles(obj, read_imported_mesh(path), 0.f);
  }
  // STL shares no vertices: they are welded by position, and its facet
  // normals (all +x here) are replaced by smooth ones.
  const fs::path stl = temporary.path() / "roof.stl";
  write_file(stl, binary_roof_stl(obj));
  expect_same_triangles(obj, read_imported_mesh(stl), 0.f);
  expect_same_triangles(obj, read_imported_mesh(kMeshes / "roof.stl"), 1e-6f);  // ASCII STL
}

// The tallies reach the scene: an STL's facets (binary: its count; ASCII:
// its facet blocks) against the triangles Assimp returns, a PLY's faces.
TEST(MeshImport, FaceTalliesOfStlAndPlyFiles) {
  const testing::TemporaryDirectory temporary("quiver_mesh_test");
  const SceneDesc obj = read_obj_scene(kObj / "roof.obj");
  const fs::path stl = temporary.path() / "roof.stl";
  write_file(stl, binary_roof_stl(obj));
  const fs::path ply = temporary.path() / "roof.ply";
  write_file(ply, binary_roof_ply(obj, false));
  for (const fs::path& path : {stl, kMeshes / "roof.stl", ply}) {
    const SceneDesc scene = read_imported_mesh(path);
    ASSERT_EQ(scene.face_tallies.size(), 1u) << path;
    EXPECT_EQ(scene.face_tallies[0].file, path.string());
    EXPECT_EQ(scene.face_tallies[0].declared, obj.triangles.size()) << path;
    EXPECT_EQ(scene.face_tallies[0].kept, obj.triangles.size()) << path;
    EXPECT_TRUE(scene.warnings.empty()) << path;
  }
}

// STL states no up axis; CAD and printing tools take +z, so its scenes say
// so for the default view; PLY and OBJ state none.
TEST(MeshImport, StlScenesAreZUp) {
  const SceneDesc stl = read_imported_mesh(kMeshes / "roof.stl");
  ASSERT_TRUE(stl.model_up.has_value());
  EXPECT_EQ(stl.model_up->axis.z, 1.f);
  EXPECT_EQ(stl.model_up->axis.x, 0.f);
  EXPECT_EQ(stl.model_up->axis.y, 0.f);
  EXPECT_NE(stl.model_up->convention.find("STL"), std::string::npos) << stl.model_up->convention;
  EXPECT_FALSE(read_obj_scene(kObj / "roof.obj").model_up.has_value());
}

// An ASCII PLY header: `vertices` of x, y, z and then `more` (property
// lines), `faces` of uint vertex-index lists.
std::string ascii_ply_header(int vertices, std::string_view more, int faces) {
  return "ply\nformat ascii 1.0\nelement vertex " + std::to_string(vertices) +
         "\nproperty float x\nproperty float y\nproperty float z\n" + std::string(more) + "element face " +
         std::to_string(faces) + "\nproperty list uchar uint vertex_indices\nend_header\n";
}

TEST(MeshImport, PlyNormalsAndTextureCoordinatesAreKeptAndPolygonsBecomeFans) {
  const testing::TemporaryDirectory temporary("quiver_mesh_test");
  const fs::path path = temporary.path() / "quad.ply";
  write_file(path, ascii_ply_header(4,
                                    "property float nx\nproperty float ny\nproperty float nz\nproperty float s\n"
                                    "property float t\n",
                                    1) +
                       "0 0 0 0 0 1 0 0\n1 0 0 0 0 1 1 0\n1 1 0 0 0 1 1 1\n0 1 0 0.6 0 0.8 0 1\n4 0 1 2 3\n");
  const SceneDesc scene = read_imported_mesh(path);
  ASSERT_EQ(scene.triangles.size(), 2u);
  for (const SceneTriangle& t : scene.triangles) {
    ASSERT_TRUE(t.triangle.normals.has_value());
    ASSERT_TRUE(t.triangle.uvs.has_value());
    for (std::size_t k = 0; k < 3; ++k) {
      // Each corner's uv is its position's x, y here; vertex 3's normal is its own.
      EXPECT_EQ((*t.triangle.uvs)[k][0], t.triangle.p[k].x);
      EXPECT_EQ((*t.triangle.uvs)[k][1], t.triangle.p[k].y);
      const bool corner3 = t.triangle.p[k].x == 0.f && t.triangle.p[k].y == 1.f;
      EXPECT_FLOAT_EQ((*t.triangle.normals)[k].x, corner3 ? 0.6f : 0.f);
    }
  }
}

// A PLY's quads are fanned from their first corner (convex) and their
// triangles' corners ordered as Assimp's n-gon encoding leaves them: a quad
// whose first corner is the previous triangle's first starts both its
// triangles at the corner it fans to last, (a, b, c) as (c, a, b) and
// (a, c, d) as (c, d, a).
TEST(MeshImport, PlyQuadsKeepAssimpsCornerOrder) {
  const std::string ply =
      ascii_ply_header(6, "", 2) + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n-1 1 0\n-1 0 0\n4 0 1 2 3\n4 0 3 4 5\n";
  const std::array<Vec3<float>, 6> vertex{{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {-1, 1, 0}, {-1, 0, 0}}};
  const std::array<std::array<int, 3>, 4> expected{{{0, 1, 2}, {0, 2, 3}, {4, 0, 3}, {4, 5, 0}}};
  const SceneDesc scene = read_mesh_bytes(ply, "quads.ply", 0.0);
  ASSERT_EQ(scene.triangles.size(), expected.size());
  for (std::size_t t = 0; t < expected.size(); ++t) {
    for (std::size_t k = 0; k < 3; ++k) {
      const Vec3<float>& p = scene.triangles[t].triangle.p[k];
      const Vec3<float>& q = vertex[static_cast<std::size_t>(expected[t][k])];
      EXPECT_TRUE(p.x == q.x && p.y == q.y && p.z == q.z)
          << "triangle " << t << " corner " << k << " is not vertex " << expected[t][k];
    }
  }
}

// A triangle whose file normals are not all finite, at any corner, gets
// computed ones instead; the others keep the file's. (PLY refuses such a
// number; a glTF's normals come through Assimp as they are.)
TEST(MeshImport, NormalsThatAreNotFiniteAtAnyCornerAreReplaced) {
  const testing::TemporaryDirectory temporary("quiver_mesh_test");
  for (int bad = 0; bad < 3; ++bad) {
    SCOPED_TRACE(bad);
    // Two triangles facing +z, (0, 1, 2) and (3, 4, 5); vertex 3 + bad's normal NaN.
    std::vector<float> floats;
    for (int v = 0; v < 6; ++v) floats.insert(floats.end(), {float(v % 3 == 1), float(v % 3 == 2), float(v / 3)});
    for (int v = 0; v < 6; ++v) {
      floats.insert(floats.end(), {v == 3 + bad ? std::numeric_limits<float>::quiet_NaN() : 0.f, 0.f, 1.f});
    }
    std::string buffer(reinterpret_cast<const char*>(floats.data()), floats.size() * sizeof(float));
    for (const std::uint16_t index : {0, 1, 2, 3, 4, 5}) buffer.append(reinterpret_cast<const char*>(&index), 2);
    write_file(temporary.path() / "two.bin", buffer);
    const fs::path path = temporary.path() / "two.gltf";
    write_file(path, R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2}]}],
      "buffers": [{"uri": "two.bin", "byteLength": 156}],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 72}, {"buffer": 0, "byteOffset": 72, "byteLength": 72},
                      {"buffer": 0, "byteOffset": 144, "byteLength": 12}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 6, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 1]},
                    {"bufferView": 1, "componentType": 5126, "count": 6, "type": "VEC3"},
                    {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}]})");
    const SceneDesc scene = read_imported_mesh(path);
    ASSERT_EQ(scene.triangles.size(), 2u);
    for (const SceneTriangle& t : scene.triangles) {
      if (!t.triangle.normals) continue;  // faceted: the geometric normal
      for (const Vec3<float>& n : *t.triangle.normals) {
        EXPECT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z));
      }
    }
    EXPECT_TRUE(scene.triangles[0].triangle.normals.has_value());  // the file's, all finite
  }
}

// Defects of the PLY path through Assimp, each now read fully or refused
// where the file is wrong.
TEST(MeshImport, PlyStripsShortFacesBadTokensAndExtremeCoordinates) {
  const testing::TemporaryDirectory temporary("quiver_mesh_test");
  const fs::path path = temporary.path() / "strips.ply";
  const std::string file = path.string();
  const std::string vertices = "element vertex 6\nproperty float x\nproperty float y\nproperty float z\n";
  // A binary strip with a restart: four triangles (Assimp read one).
  std::string bytes = "ply\nformat binary_little_endian 1.0\n" + vertices +
                      "element tristrips 1\nproperty list int int vertex_indices\nend_header\n";
  for (float c : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f, 1.f, 1.f, 0.f, 0.f, 2.f, 0.f, 1.f, 2.f, 0.f}) {
    put(bytes, c);
  }
  put<std::int32_t>(bytes, 9);
  for (std::int32_t v : {0, 1, 2, 3, -1, 2, 3, 4, 5}) put(bytes, v);
  write_file(path, bytes);
  EXPECT_EQ(read_imported_mesh(path, kDefaultCreaseAngleDegrees, true).triangles.size(), 4u);

  // A face of no vertices beside a triangle (Assimp aborted): dropped with a warning.
  const std::string ascii = "ply\nformat ascii 1.0\n" + vertices +
                            "element face 2\nproperty list uchar int vertex_indices\nend_header\n"
                            "0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 2 0\n1 2 0\n";
  write_file(path, ascii + "3 0 1 2\n0\n");
  const SceneDesc scene = read_imported_mesh(path);
  EXPECT_EQ(scene.triangles.size(), 1u);
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_NE(scene.warnings[0].find("expected faces of at least 3 vertices"), std::string::npos) << scene.warnings[0];
  EXPECT_THROW(read_imported_mesh(path, kDefaultCreaseAngleDegrees, true), ParseError);

  // Tokens that are no numbers of their type (Assimp read them).
  for (const auto& [data, message] : std::vector<std::pair<std::string, std::string>>{
           {"3 0 1.5 2\n3 0 1 2\n", ":16:5: expected a whole number"},
           {"3 0 nan 2\n3 0 1 2\n", ":16:5: expected a whole number"},
           {"3 0 1\n3 0 1 2\n", ":16:6: expected a value ('vertex_indices' of element 'face'), found end of line"}}) {
    write_file(path, ascii + data);
    EXPECT_EQ(import_error(path).rfind(file + message, 0), 0u) << import_error(path);
  }
  std::string comma = ascii;
  comma.replace(comma.find("1 2 0\n"), 5, "1,5 2 0");
  write_file(path, comma + "3 0 1 2\n3 0 1 3\n");
  EXPECT_EQ(import_error(path).rfind(file + ":15:1: expected a number ('x' of element 'vertex'), found '1,5'", 0), 0u)
      << import_error(path);
  // A coordinate beyond OBJ's bound, at its place (Assimp read it).
  std::string extreme = ascii;
  extreme.replace(extreme.find("0 2 0\n"), 5, "0 -3.4028e38 0");
  write_file(path, extreme + "3 0 1 2\n3 0 1 3\n");
  EXPECT_EQ(import_error(path).rfind(file + ":14:3: expected a number from -3.4e38 to 3.4e38", 0), 0u)
      << import_error(path);
}

TEST(MeshImport, GltfGetsItsNodeTransformAndBaseColourAndStaysFacetedWithoutNormals) {
  const SceneDesc scene = read_imported_mesh(kMeshes / "triangle.gltf");
  ASSERT_EQ(scene.triangles.size(), 1u);
  const TriangleDesc& t = scene.triangles[0].triangle;
  EXPECT_FALSE(t.normals.has_value());  // glTF: flat shading when normals are absent
  for (std::size_t k = 0; k < 3; ++k) EXPECT_EQ(t.p[k].z, 2.f);  // the node's translation
  EXPECT_EQ(t.p[0].x + t.p[1].x + t.p[2].x, 1.f);
  const MaterialDesc& m = scene.materials.at(scene.triangles[0].material);
  EXPECT_EQ(m.color.x, 0.8f);
  EXPECT_EQ(m.color.y, 0.25f);
  EXPECT_EQ(m.color.z, 0.125f);
  EXPECT_FALSE(m.two_sided);  // glTF's doubleSided defaults to false
}

// triangle.gltf with its nodes replaced by `nodes` (JSON), all placing mesh 0.
std::string triangle_gltf_with_nodes(const std::string& nodes, const std::string& scene_nodes) {
  return testing::gltf_with_nodes(file_bytes(kMeshes / "triangle.gltf"), nodes, scene_nodes);
}

// Each node that names a mesh places it; a mirroring node keeps the file's
// front faces at the front (glTF: its winding turns clockwise).
TEST(MeshImport, GltfNodesPlaceTheirMeshesAndAMirrorKeepsTheFront) {
  const testing::TemporaryDirectory temporary("quiver_mesh_test");
  const fs::path path = temporary.path() / "nodes.gltf";
  // The second node mirrors x and is a child of a node moved along z.
  write_file(path, triangle_gltf_with_nodes(R"([{"mesh": 0}, {"translation": [0, 0, 5], "children": [2]},
      {"mesh": 0, "scale": [-1, 1, 1]}])",
                                            "[0, 1]"));
  const SceneDesc scene = read_imported_mesh(path);
  ASSERT_EQ(scene.triangles.size(), 2u);
  for (const SceneTriangle& t : scene.triangles) {
    const Vec3<float>& a = t.triangle.p[0];
    const Vec3<float>& b = t.triangle.p[1];
    const Vec3<float>& c = t.triangle.p[2];
    // The front (counter-clockwise) faces +z in both, as in the file.
    const float nz = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    EXPECT_GT(nz, 0.f);
  }
  const bool mirrored_first = scene.triangles[0].triangle.p[0].z == 5.f;
  const TriangleDesc& mirrored = scene.triangles[mirrored_first ? 0 : 1].triangle;
  const TriangleDesc& plain = scene.triangles[mirrored_first ? 1 : 0].triangle;
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(plain.p[k].z, 0.f);
    EXPECT_EQ(mirrored.p[k].z, 5.f);
    EXPECT_LE(mirrored.p[k].x, 0.f);
  }
  // Placements count against the triangle bound before they are copied.
  try {
    read_imported_mesh(path, kDefaultCreaseAngleDegrees, false, 1);
    ADD_FAILURE() << "no ParseError";
  } catch (const ParseError& error) {
    EXPECT_EQ(std::string(error.what()),
              path.string() + ": expected at most 1 triangles once the file's nodes place its meshes, found 2");
  }
}

// A node that rotates and scales unevenly turns the file's normals by the
// inverse transpose of its linear part (a normal stays perpendicular to the
// surface), renormalised; the positions by the map itself.
TEST(MeshImport, GltfNormalsFollowTheNodeByItsInverseTranspose) {
  const testing::TemporaryDirectory temporary("quiver_mesh_test");
  const std::array<Vec3<float>, 3> positions{{{0.f, 0.f, 0.f}, {1.f, 0.f, 0.f}, {0.f, 1.f, 0.f}}};
  const std::array<Vec3<float>, 3> normals{{{0.6f, 0.f, 0.8f}, {0.f, 0.6f, 0.8f}, {0.f, 0.f, 1.f}}};
  const std::uint16_t indices[4] = {0, 1, 2, 0};
  std::string buffer(80, '\0');
  for (std::size_t k = 0; k < 3; ++k) {
    std::memcpy(buffer.data() + 12 * k, &positions[k].x, 12);
    std::memcpy(buffer.data() + 36 + 12 * k, &normals[k].x, 12);
  }
  std::memcpy(buffer.data() + 72, indices, 8);
  write_file(temporary.path() / "turned.bin", buffer);
  // Rotated a quarter turn about z, after a scale of 4 along y.
  write_file(temporary.path() / "turned.gltf", R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
    "nodes": [{"mesh": 0, "rotation": [0, 0, 0.70710678, 0.70710678], "scale": [1, 4, 1]}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2}]}],
    "buffers": [{"byteLength": 80, "uri": "turned.bin"}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 36},
                    {"buffer": 0, "byteOffset": 72, "byteLength": 6}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
                  {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
                  {"bufferView": 2, "componentType": 5123, "count": 3, "type": "SCALAR"}]})");
  const SceneDesc scene = read_imported_mesh(temporary.path() / "turned.gltf");
  ASSERT_EQ(scene.triangles.size(), 1u);
  const TriangleDesc& t = scene.triangles[0].triangle;
  ASSERT_TRUE(t.normals.has_value());
  // The map: (x, y, z) -> (-4y, x, z); its inverse transpose: (x, y, z) -> (-y / 4, x, z).
  const auto placed = [](const Vec3<float>& p) { return Vec3<float>{-4.f * p.y, p.x, p.z}; };
  const auto turned = [](const Vec3<float>& n) { return normalize(Vec3<float>{-n.y / 4.f, n.x, n.z}); };
  for (std::size_t k = 0; k < 3; ++k) {
    std::size_t file_vertex = 3;
    for (std::size_t f = 0; f < 3; ++f) {
      if (length(t.p[k] - placed(positions[f])) < 1e-5f) file_vertex = f;
    }
    ASSERT_LT(file_vertex, 3u) << "corner " << k << " is no placed file vertex";
    const Vec3<float> expected = turned(normals[file_vertex]);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR((*t.normals)[k][a], expected[a], 1e-5f) << "corner " << k << " axis " << a;
  }
}

// glTF's glass (KHR_materials_transmission, KHR_materials_ior) refracts.
TEST(MeshImport, GltfTransmissionAndIorBecomeRefraction) {
  const testing::TemporaryDirectory temporary("quiver_mesh_test");
  std::string json = file_bytes(kMeshes / "triangle.gltf");
  const std::size_t at = json.find("\"pbrMetallicRoughness\"");
  ASSERT_NE(at, std::string::npos);
  json.insert(at, R"("extensions": {"KHR_materials_transmission": {"transmissionFactor": 0.75},
                   "KHR_materials_ior": {"ior": 1.45}}, )");
  json.insert(json.find('{') + 1, R"( "extensionsUsed": ["KHR_materials_transmission", "KHR_materials_ior"],)");
  const fs::path path = temporary.path() / "glass.gltf";
  write_file(path, json);
  const SceneDesc scene = read_imported_mesh(path);
  const MaterialDesc& glass = scene.materials.at(scene.triangles.at(0).material);
  EXPECT_EQ(glass.kt, 0.75f);
  EXPECT_EQ(glass.ior, 1.45f);
  EXPECT_EQ(glass.kd, MaterialDesc{}.kd * 0.25f);
  EXPECT_TRUE(glass.two_sided);
  // Without the extensions: an opaque diffuse surface, as before.
  const MaterialDesc& plain = read_imported_mesh(kMeshes / "triangle.gltf").materials.at(0);
  EXPECT_EQ(plain.kt, 0.f);
  EXPECT_EQ(plain.ior, MaterialDesc{}.ior);
  EXPECT_EQ(plain.kd, MaterialDesc{}.kd);
}

// glTF's metallic-roughness factors by io/mesh_import.cpp's rule: a polished
// metal is a mirror with sharp highlights, a half-rough dielectric keeps
// most of its diffuse colour, the defaults (rough) change nothing; a
// metallicRoughnessTexture is named in a warning, its factors used.
TEST(MeshImport, GltfMetallicRoughnessBecomesMirrorAndHighlights) {
  const testing::TemporaryDirectory temporary("quiver_mesh_test");
  const auto material_of = [&](const std::string& factors) {
    std::string json = file_bytes(kMeshes / "triangle.gltf");
    const std::size_t at = json.find("\"baseColorFactor\"");
    json.insert(at, factors);
    const fs::path path = temporary.path() / "metal.gltf";
    write_file(path, json);
    const SceneDesc scene = read_imported_mesh(path);
    return scene.materials.at(scene.triangles.at(0).material);
  };
  const MaterialDesc metal = material_of(R"("metallicFactor": 1.0, "roughnessFactor": 0.0, )");
  EXPECT_EQ(metal.kr, 1.f);
  EXPECT_EQ(metal.ks, 1.f);
  EXPECT_EQ(metal.kd, 0.f);
  EXPECT_EQ(metal.shininess, 1e4f);
  // glTF's metallicFactor defaults to 1: polished and without it, a metal.
  const MaterialDesc unstated = material_of(R"("roughnessFactor": 0.0, )");
  EXPECT_EQ(unstated.kr, 1.f);
  EXPECT_EQ(unstated.kd, 0.f);
  const MaterialDesc satin = material_of(R"("metallicFactor": 0.0, "roughnessFactor": 0.5, )");
  EXPECT_FLOAT_EQ(satin.kr, 0.25f * 0.04f);
  EXPECT_FLOAT_EQ(satin.ks, 0.25f * 0.04f);
  EXPECT_FLOAT_EQ(satin.kd, MaterialDesc{}.kd * (1.f - 0.01f));
  EXPECT_FLOAT_EQ(satin.shininess, 2.f / (0.25f * 0.25f) - 2.f);
  const MaterialDesc rough = read_imported_mesh(kMeshes / "triangle.gltf").materials.at(0);
  EXPECT_EQ(rough.kr, 0.f);
  EXPECT_EQ(rough.ks, 0.f);
  EXPECT_EQ(rough.kd, MaterialDesc{}.kd);

  std::string json = file_bytes(kMeshes / "textured.gltf");
  const std::size_t at = json.find("\"baseColorTexture\"");
  ASSERT_NE(at, std::string::npos);
  json.insert(at, R"("metallicRoughnessTexture": {"index": 0}, "metallicFactor": 0.0, "roughnessFactor": 0.0, )");
  const fs::path path = temporary.path() / "textured_metal.gltf";
  write_file(path, json);
  const SceneDesc scene = read_imported_mesh(path);
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_NE(scene.warnings[0].find("a metallicRoughnessTexture; its factors alone are used"), std::string::npos)
      << scene.warnings[0];
  EXPECT_FLOAT_EQ(scene.materials.at(scene.triangles.at(0).material).kr, 0.04f);
  EXPECT_THROW(read_imported_mesh(path, 60.0, true), ParseError);
}

// A GLB file of a JSON chunk and a binary chunk (each padded to 4 bytes).
std::string glb(std::string json, std::string binary, std::uint32_t stated_length_extra = 0) {
  while (json.size() % 4 != 0) json += ' ';
  while (binary.size() % 4 != 0) binary += '\0';
  std::string bytes = "glTF";
  put<std::uint32_t>(bytes, 2);
  put<std::uint32_t>(bytes, static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + binary.size()) +
                                stated_length_extra);
  put<std::uint32_t>(bytes, static_cast<std::uint32_t>(json.size()));
  put<std::uint32_t>(bytes, 0x4E4F534A);
  bytes += json;
  put<std::uint32_t>(bytes, static_cast<std::uint32_t>(binary.size()));
  put<std::uint32_t>(bytes, 0x004E4942);
  bytes += binary;
  return bytes;
}

// A .glb of triangle.gltf's JSON with its buffer in the binary chunk.
std::string glb_of_triangle(std::uint32_t stated_length_extra = 0) {
  std::string json = file_bytes(kMeshes / "triangle.gltf");
  const std::size_t uri = json.find("\"uri\"");
  const std::size_t data = json.find("base64,", uri) + 7;
  const std::size_t end = json.find('"', data);
  const std::string binary = base64_decoded(std::string_view(json).substr(data, end - data));
  json.erase(uri, end + 1 - uri);
  json.erase(json.rfind(',', uri), uri - json.rfind(',', uri));  // the comma before "uri"
  return glb(json, binary, stated_length_extra);
}

TEST(MeshImport, GlbReadsAsItsGltf) {
  const testing::TemporaryDirectory temporary("quiver_mesh_test");
  const fs::path path = temporary.path() / "triangle.glb";
  write_file(path, glb_of_triangle());
  expect_same_triangles(read_imported_mesh(kMeshes / "triangle.gltf"), read_imported_mesh(path), 0.f);
  write_file(path, glb_of_triangle(4));
  EXPECT_NE(import_error(path).find(": byte 8: expected the GLB length "), std::string::npos) << import_error(path);
}

// A GLB of the unit square in z = 0 (two triangles, uvs as glTF writes
// them: (0, 0) at the image's top left, here the square's corner (0, 1)),
// whose base colour texture is `image`, stored as most GLB files store it:
// in the binary chunk (bufferView 3).
std::string textured_glb(const std::string& image, const std::string& sampler = "") {
  std::string binary;
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 1.f, 1.f, 0.f, 0.f, 1.f, 0.f}) put(binary, v);  // 48 bytes
  for (float v : {0.f, 1.f, 1.f, 1.f, 1.f, 0.f, 0.f, 0.f}) put(binary, v);                      // 32 bytes
  for (std::uint16_t i : {0, 1, 2, 0, 2, 3}) put(binary, i);                                   // 12 bytes
  const std::string image_offset = std::to_string(binary.size());
  binary += image;
  const std::string json =
      R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 0}]}],
 "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}, "doubleSided": true}],
 "textures": [{"source": 0)" + std::string(sampler.empty() ? "" : R"(, "sampler": 0)") +
      R"(}], "images": [{"bufferView": 3, "mimeType": "image/png"}],)" +
      (sampler.empty() ? std::string() : R"( "samplers": [)" + sampler + "],") + R"(
 "buffers": [{"byteLength": )" +
      std::to_string(binary.size()) + R"(}],
 "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 32},
                 {"buffer": 0, "byteOffset": 80, "byteLength": 12},
                 {"buffer": 0, "byteOffset": )" +
      image_offset + R"(, "byteLength": )" + std::to_string(image.size()) + R"(}],
 "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
               {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
               {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}]})";
  return glb(json, binary);
}

TEST(MeshImport, AGlbsEmbeddedTextureIsDecodedLikeTheSameImageFile) {
  const testing::TemporaryDirectory temporary("quiver_mesh_test");
  const fs::path checker = kObj / "tex" / "checker.png";
  const fs::path path = temporary.path() / "textured.glb";
  write_file(path, textured_glb(file_bytes(checker)));
  const SceneDesc scene = load_scene(path);
  ASSERT_EQ(scene.triangles.size(), 2u);
  ASSERT_EQ(scene.textures.size(), 1u);
  const TextureDesc& texture = scene.textures[0];
  const TextureImage expected = read_texture_image(checker);
  EXPECT_EQ(texture.width, expected.width);
  EXPECT_EQ(texture.height, expected.height);
  EXPECT_EQ(texture.rgb, expected.rgb);
  EXPECT_TRUE(texture.encoded.empty());  // released once decoded
  EXPECT_EQ(texture.wrap, WrapMode::repeat);  // glTF's default sampler
  const MaterialDesc& m = scene.materials.at(scene.triangles[0].material);
  EXPECT_EQ(m.texture, std::optional<std::size_t>{0});
  EXPECT_TRUE(m.two_sided);
  // glTF's uv (0, 0) is the image's top left; quiver's v = 1 is its top row.
  for (const SceneTriangle& t : scene.triangles) {
    ASSERT_TRUE(t.triangle.uvs.has_value());
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_EQ((*t.triangle.uvs)[k][0], t.triangle.p[k].x);
      EXPECT_EQ((*t.triangle.uvs)[k][1], t.triangle.p[k].y);
    }
  }
  EXPECT_TRUE(scene.warnings.empty());

  // The same image as a data URI in a .gltf (tests/data/mesh/textured.gltf).
  const SceneDesc from_uri = load_scene(kMeshes / "textured.gltf");
  ASSERT_EQ(from_uri.textures.size(), 1u);
  EXPECT_EQ(from_uri.textures[0].rgb, expected.rgb);
  expect_same_triangles(scene, from_uri, 0.f);

  // The sampler's wrap (33071 CLAMP_TO_EDGE, 33648 MIRRORED_REPEAT); one wrap for both axes.
  write_file(path, textured_glb(file_bytes(checker), R"({"wrapS": 33071, "wrapT": 33071})"));
  EXPECT_EQ(load_scene(path).textures.at(0).wrap, WrapMode::clamp);
  write_file(path, textured_glb(file_bytes(checker), R"({"wrapS": 33648, "wrapT": 33648})"));
  EXPECT_EQ(load_scene(path).textures.at(0).wrap, WrapMode::mirror);
  write_file(path, textured_glb(file_bytes(checker), R"({"wrapS": 33071, "wrapT": 10497})"));
  const SceneDesc mixed = load_scene(path);
  EXPECT_EQ(mixed.textures.at(0).wrap, WrapMode::clamp);
  ASSERT_EQ(mixed.warnings.size(), 1u);
  EXPECT_NE(mixed.warnings[0].find("found different wrapS and wrapT; wrapS is used for both"), std::string::npos)
      << mixed.warnings[0];

  // Bytes that are no image: the error names the mesh and the embedded image.
  write_file(path, textured_glb("not an image at all"));
  try {
    load_scene(path);
    ADD_FAILURE() << "no ParseError";
  } catch (const ParseError& error) {
    EXPECT_EQ(std::string(error.what()).rfind(path.string() + " (embedded image): not an image", 0), 0u)
        << error.what();
  }
}

// glTF writes file names as URIs: "my%20buffer.bin" names "my buffer.bin".
TEST(MeshImport, GltfBufferAndImageUrisArePercentDecoded) {
  const testing::TemporaryDirectory temporary("quiver_mesh_test");
  const fs::path& dir = temporary.path();
  std::string json = file_bytes(kMeshes / "textured.gltf");
  // The buffer and the image out of their data URIs into files whose names have a space.
  const auto move_out = [&](const std::string& data_prefix, const std::string& name) {
    const std::size_t start = json.find(data_prefix);
    ASSERT_NE(start, std::string::npos) << data_prefix;
    const std::size_t end = json.find('"', start);
    write_file(dir / name, base64_decoded(std::string_view(json).substr(start + data_prefix.size(),
                                                                        end - start - data_prefix.size())));
    std::string encoded = name;
    encoded.replace(encoded.find(' '), 1, "%20");
    json.replace(start, end - start, encoded);
  };
  move_out("data:application/octet-stream;base64,", "square buffer.bin");
  move_out("data:image/png;base64,", "square image.png");
  write_file(dir / "square.gltf", json);
  const SceneDesc scene = load_scene(dir / "square.gltf");
  ASSERT_EQ(scene.triangles.size(), 2u);
  ASSERT_EQ(scene.textures.size(), 1u);
  EXPECT_EQ(scene.textures[0].path, (dir / "square image.png").string());
  EXPECT_EQ(scene.textures[0].rgb, read_texture_image(kObj / "tex" / "checker.png").rgb);
  EXPECT_TRUE(scene.warnings.empty());
}

TEST(MeshImport, PointsAndLinesAreAWarningOrUnderStrictAnError) {
  const testing::TemporaryDirectory temporary("quiver_mesh_test");
  std::string json = file_bytes(kMeshes / "triangle.gltf");
  // A second primitive drawing the same vertices as points (mode 0).
  const std::string primitive = "\"material\": 0\n    }";
  const std::size_t at = json.find(primitive);
  ASSERT_NE(at, std::string::npos);
  json.insert(at + primitive.size(), ", {\"attributes\": {\"POSITION\": 0}, \"mode\": 0}");
  const fs::path path = temporary.path() / "points.gltf";
  write_file(path, json);
  const SceneDesc scene = read_imported_mesh(path);
  EXPECT_EQ(scene.triangles.size(), 1u);
  ASSERT_EQ(scene.warnings.size(), 1u);
  // About the file as a whole: its name alone, no line and column.
  EXPECT_EQ(scene.warnings[0].rfind(path.string() + ": warning: expected triangles, found 3 points and lines", 0), 0u)
      << scene.warnings[0];
  try {
    read_imported_mesh(path, kDefaultCreaseAngleDegrees, true);
    ADD_FAILURE() << "no ParseError";
  } catch (const ParseError& error) {
    EXPECT_EQ(std::string(error.what()), path.string() + ": expected triangles, found 3 points and lines");
  }
}

// Counts that would make the reader allocate more than the file holds are
// refused before anything is allocated, where they are written.
TEST(MeshFileCheck, PlyCountsAreBoundedByTheBytesThatFollow) {
  const testing::TemporaryDirectory temporary("quiver_mesh_test");
  const fs::path path = temporary.path() / "bad.ply";
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                             "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string vertices = "0 0 0\n1 0 0\n0 1 0\n";
  const std::string file = path.string();

  write_file(path, "ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\nend_header\n0\n");
  EXPECT_EQ(import_error(path).rfind(file + ":3:16: expected an element count that the 2 bytes after the header "
                                            "can hold, found '4000000000'", 0),
            0u)
      << import_error(path);

  write_file(path, header + vertices + "4000000000 0 1 2\n");
  EXPECT_EQ(import_error(path).rfind(file + ":13:1: expected a list length", 0), 0u) << import_error(path);

  write_file(path, header + "0 0 0\n1 0 0\n   0 1");  // a value short (blanks keep the count within the bound)
  EXPECT_EQ(import_error(path).rfind(file + ":12:7: expected a value ('z' of element 'vertex'), found end of file", 0),
            0u)
      << import_error(path);

  write_file(path, "ply\nformat ascii 2.0\nend_header\n");
  EXPECT_EQ(import_error(path).rfind(file + ":2:14: expected the format version 1.0, found '2.0'", 0), 0u)
      << import_error(path);
  write_file(path, "ply\nformat ascii 1.0\nelement vertex 1\nproperty list float int v\nend_header\n");
  EXPECT_EQ(import_error(path).rfind(file + ":4:15: expected a list's count type", 0), 0u) << import_error(path);
  write_file(path, "ply\nformat ascii 1.0\nelement vertex 0\n");
  EXPECT_EQ(import_error(path).rfind(file + ":4:1: expected a PLY header line ending with 'end_header', found end "
                                            "of file", 0),
            0u)
      << import_error(path);
  write_file(path, "ply\ncomment x");  // no final line break (a fuzzer's find): the end is on line 2
  EXPECT_EQ(import_error(path).rfind(file + ":2:10: expected a PLY header line ending with 'end_header'", 0), 0u)
      << import_error(path);
  write_file(path, "solid\n");
  EXPECT_EQ(import_error(path).rfind(file + ":1:1: expected 'ply', the first line of a PLY file, found 'solid'", 0),
            0u)
      << import_error(path);

  // Binary: a list claiming more indices than the file holds, at its byte.
  std::string binary = "ply\nformat binary_little_endian 1.0\nelement face 1\n"
                       "property list uint int vertex_indices\nend_header\n";
  const std::size_t offset = binary.size();
  put<std::uint32_t>(binary, 0x40000000);
  put<std::int32_t>(binary, 0);
  write_file(path, binary);
  EXPECT_EQ(import_error(path), file + ": byte " + std::to_string(offset) +
                                    ": expected a list length that the rest of the file can hold, found 1073741824");
  binary.resize(offset + 2);  // the count itself cut short: the element count is more than the bytes hold
  write_file(path, binary);
  EXPECT_EQ(import_error(path), file + ":3:14: expected an element count that the 2 bytes after the header can "
                                       "hold, found '1'");
}

TEST(MeshFileCheck, StlAndGltfStateTheirSizesTruthfully) {
  const testing::TemporaryDirectory temporary("quiver_mesh_test");
  const SceneDesc obj = read_obj_scene(kObj / "roof.obj");
  std::string stl = binary_roof_stl(obj);
  stl[80] = 3;  // three triangles stated, two present
  const fs::path path = temporary.path() / "bad.stl";
  write_file(path, stl);
  EXPECT_EQ(import_error(path), path.string() + ": byte 80: expected a binary STL's triangle count N with 84 + 50 N "
                                                "= 184, the file's size (or an ASCII STL starting 'solid'), found 3");

  const std::string json = file_bytes(kMeshes / "triangle.gltf");
  const fs::path gltf = temporary.path() / "bad.gltf";
  std::string lying = json;
  const std::size_t length = lying.find("\"byteLength\": 44");
  ASSERT_NE(length, std::string::npos);
  lying.replace(length, 16, "\"byteLength\": 99999999999");
  write_file(gltf, lying);
  EXPECT_EQ(import_error(gltf), gltf.string() + ": expected buffers[0].byteLength to be at most the 44 bytes of its "
                                                "data URI, found 99999999999");
  std::string missing = json;
  const std::size_t uri = missing.find("data:");
  missing.replace(uri, missing.find('"', uri) - uri, "nowhere.bin");
  write_file(gltf, missing);
  EXPECT_EQ(import_error(gltf), gltf.string() + ": expected buffers[0]'s file 'nowhere.bin' beside it, found no "
                                                "such file");
  // A number past double's range is nlohmann's out_of_range, not a parse error (a fuzzer's find).
  write_file(gltf, "{\"asset\": {\"version\": \"2.0\"}, \"scene\": 1e999}\n");
  EXPECT_NE(import_error(gltf).find(gltf.string() + ": expected glTF's JSON, found: [json.exception.out_of_range"),
            std::string::npos)
      << import_error(gltf);
  write_file(gltf, "{\"asset\": {\"version\": \"2.0\"},\n \"buffers\": [,]}\n");
  EXPECT_EQ(import_error(gltf).rfind(gltf.string() + ":2:14: expected glTF's JSON, found ',]}'", 0), 0u)
      << import_error(gltf);
}

// The headers' own sizes: an STL of exactly its 84-byte header that states
// a triangle is a wrong count (not a short header), and a GLB one byte short
// of its 12-byte header is a bad header (nothing past it is read).
TEST(MeshFileCheck, HeadersAtTheirExactSizesAndOneByteShort) {
  std::string stl(84, '\0');
  stl[80] = 1;
  try {
    check_stl(stl, "h.stl");
    ADD_FAILURE() << "an 84-byte STL stating a triangle was accepted";
  } catch (const ParseError& error) {
    EXPECT_EQ(std::string(error.what()), "h.stl: byte 80: expected a binary STL's triangle count N with 84 + 50 N "
                                         "= 84, the file's size (or an ASCII STL starting 'solid'), found 1");
  }
  const std::string glb = std::string("glTF") + std::string("\x02\0\0\0", 4) + std::string("\x0b\0\0", 3);
  ASSERT_EQ(glb.size(), 11u);
  try {
    check_gltf(glb, "h.glb", ".", PathRule{}, true, 1u << 20, 1000);
    ADD_FAILURE() << "an 11-byte GLB was accepted";
  } catch (const ParseError& error) {
    EXPECT_EQ(std::string(error.what()), "h.glb: byte 0: expected a GLB header starting 'glTF', found 'glTF'");
  }
}

// A GLB's header states the file's length exactly: one whose stated length
// is short of the file (the last bytes of its binary chunk, or a whole chunk
// after it, beyond the length) is refused at byte 8, naming the file's size
// and the length found, even though its chunks read well to the file's end.
TEST(MeshFileCheck, AGlbLongerThanItsStatedLengthIsRefused) {
  const std::string whole = glb_of_triangle();
  EXPECT_NO_THROW(check_gltf(whole, "t.glb", ".", PathRule{}, true, 1u << 20, 1000));
  std::string extra_chunk = whole;  // an empty chunk past the stated length
  put<std::uint32_t>(extra_chunk, 0);
  put<std::uint32_t>(extra_chunk, 0x004E4942);
  const std::string short_by_four = glb_of_triangle(static_cast<std::uint32_t>(-4));
  const std::pair<const std::string*, std::size_t> cases[] = {{&short_by_four, whole.size() - 4},
                                                              {&extra_chunk, whole.size()}};
  for (const auto& [bytes, stated] : cases) {
    ASSERT_LT(stated, bytes->size());
    try {
      check_gltf(*bytes, "t.glb", ".", PathRule{}, true, 1u << 20, 1000);
      ADD_FAILURE() << "a GLB of " << bytes->size() << " bytes stating " << stated << " was accepted";
    } catch (const ParseError& error) {
      EXPECT_EQ(std::string(error.what()), "t.glb: byte 8: expected the GLB length " + std::to_string(bytes->size()) +
                                               ", the file's size, found " + std::to_string(stated));
    }
  }
}

// A binary STL may state up to kMaxObjTriangles triangles, not one more:
// the bytes of a file of exactly that many, mapped without being touched
// (anonymous pages read as zeros; only the count is written).
TEST(MeshFileCheck, AnStlOfAsManyTrianglesAsTheBoundPassesAndOneMoreDoesNot) {
  for (const std::uint64_t triangles : {std::uint64_t{kMaxObjTriangles}, std::uint64_t{kMaxObjTriangles} + 1}) {
    const std::size_t size = std::size_t(84 + 50 * triangles);
    void* mapped = ::mmap(nullptr, size, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    ASSERT_NE(mapped, MAP_FAILED);
    auto* bytes = static_cast<unsigned char*>(mapped);
    for (int k = 0; k < 4; ++k) bytes[80 + k] = static_cast<unsigned char>(triangles >> (8 * k));
    const std::string_view view(static_cast<const char*>(mapped), size);
    if (triangles == kMaxObjTriangles) {
      EXPECT_EQ(check_stl(view, "big.stl").triangles, kMaxObjTriangles);
    } else {
      EXPECT_THROW(check_stl(view, "big.stl"), ParseError);
    }
    ::munmap(mapped, size);
  }
}

// A glTF's JSON of exactly the value bound is parsed (and then found to be
// no glTF document); one value more is refused before parsing.
TEST(MeshFileCheck, GltfJsonOfTheValueBoundIsParsedAndOneMoreIsRefused) {
  // An array of n zeros: n + 1 values.
  const auto zeros = [](std::size_t n) {
    std::string text = "[0";
    text.reserve(2 * n + 1);
    for (std::size_t i = 1; i < n; ++i) text += ",0";
    return text + "]";
  };
  const auto error_of = [](const std::string& json) {
    try {
      check_gltf(json, "values.gltf", ".", PathRule{}, false, kMaxObjBytes, kMaxObjTriangles);
    } catch (const ParseError& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  const std::string bound_error = "JSON of at most 4194304 values";
  const std::string at_bound = error_of(zeros(kMaxGltfJsonValues - 1));
  EXPECT_EQ(at_bound.find(bound_error), std::string::npos) << at_bound;
  EXPECT_NE(at_bound, "no error");
  const std::string past = error_of(zeros(kMaxGltfJsonValues));
  EXPECT_NE(past.find(bound_error), std::string::npos) << past;
}

TEST(MeshImport, AssimpsOwnErrorsNameTheFileAndAnEmptyMeshIsAnError) {
  const testing::TemporaryDirectory temporary("quiver_mesh_test");
  const fs::path empty = temporary.path() / "empty.ply";
  write_file(empty, "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
                    "property float z\nend_header\n");
  EXPECT_EQ(import_error(empty), empty.string() + ": expected at least one triangle, found none");
  // Valid JSON that is no glTF Assimp can read: its message, after the file's name.
  const fs::path gltf = temporary.path() / "wrong.gltf";
  write_file(gltf, "{\"asset\": {\"version\": \"1.0\"}}\n");
  EXPECT_EQ(import_error(gltf).rfind(gltf.string() + ": Assimp: ", 0), 0u) << import_error(gltf);
}

TEST(MeshAppend, TrianglesLeftCountDownToZeroAtTheBound) {
  EXPECT_EQ(triangles_left(0), kMaxObjTriangles);
  EXPECT_EQ(triangles_left(1), kMaxObjTriangles - 1);
  EXPECT_EQ(triangles_left(kMaxObjTriangles - 1), 1u);
  EXPECT_EQ(triangles_left(kMaxObjTriangles), 0u);
  EXPECT_EQ(triangles_left(kMaxObjTriangles + 1), 0u);
}

TEST(MeshAppend, APlyMeshIsPlacedAndCountedLikeAnObj) {
  SceneDesc from_obj, from_ply;
  from_obj.materials.push_back(MaterialDesc{});
  from_ply.materials.push_back(MaterialDesc{});
  const std::array<float, 16> shifted{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 0, 0, 1};
  append_mesh(kObj / "roof.obj", shifted, std::size_t{0}, from_obj);
  append_mesh(kMeshes / "roof.ply", shifted, std::size_t{0}, from_ply);
  expect_same_triangles(from_obj, from_ply, 1e-6f);
  EXPECT_EQ(from_ply.triangles[0].triangle.p[0].x, 5.f);
  EXPECT_EQ(from_ply.source_files, std::vector<std::string>{(kMeshes / "roof.ply").string()});
  EXPECT_THROW(append_mesh(kMeshes / "roof.txt", shifted, std::nullopt, from_ply), std::invalid_argument);
}

// Assimp's public test models (Debian's assimp-testmodels): Khronos glTF
// samples, Blender and 3ds Max exports, and files broken on purpose.
fs::path public_models() {
  const char* env = std::getenv("QUIVER_ASSIMP_MODELS_DIR");
  return env != nullptr && *env != '\0' ? fs::path(env) : fs::path(QUIVER_ASSIMP_MODELS_DIR);
}

// Every PLY, glTF and STL file there either loads or is one ParseError
// naming it; never another exception.
TEST(MeshImportPublicModels, EveryFileLoadsOrIsAnErrorNamingIt) {
  const fs::path root = public_models();
  if (!fs::is_directory(root)) {
    GTEST_SKIP() << root << " not found: apt-get install assimp-testmodels, or set QUIVER_ASSIMP_MODELS_DIR";
  }
  std::size_t loaded = 0, refused = 0;
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(root)) {
    const std::string extension = entry.path().extension().string();
    std::string lower;
    for (char c : extension) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (!entry.is_regular_file() || !is_imported_mesh_extension(lower)) continue;
    try {
      const SceneDesc scene = load_scene(entry.path());
      EXPECT_FALSE(scene.triangles.empty()) << entry.path();
      ++loaded;
    } catch (const ParseError& error) {
      EXPECT_EQ(std::string(error.what()).rfind(entry.path().string(), 0), 0u) << error.what();
      ++refused;
    }
  }
  // Debian 12's assimp-testmodels 5.2.5: 70 such files (39 load; the Draco
  // engine and a bufferView past its buffer are among those refused).
  EXPECT_GE(loaded, 38u);
  EXPECT_GE(refused, 10u);
}

// glTF's seven primitive modes (the Khronos asset generator's files):
// triangles, strips and fans kept whole, points and lines counted and named;
// and a file with an index out of range, whose triangle Assimp drops: the
// tally against the triangles the accessors declare names the loss.
TEST(MeshImportPublicModels, GltfFacesOfEveryModeAreTalliedAndALossIsNamed) {
  const fs::path root = public_models();
  if (!fs::is_directory(root)) {
    GTEST_SKIP() << root << " not found: apt-get install assimp-testmodels, or set QUIVER_ASSIMP_MODELS_DIR";
  }
  std::size_t files = 0, with_points_or_lines = 0;
  for (const auto& entry : fs::directory_iterator(root / "glTF2" / "glTF-Asset-Generator" / "Mesh_PrimitiveMode")) {
    if (entry.path().extension() != ".gltf") continue;
    SceneDesc scene;
    try {
      scene = read_imported_mesh(entry.path());
    } catch (const ParseError&) {
      continue;  // points or lines alone: no triangle to draw (MeshImportPublicModels.EveryFileLoadsOrIsAnErrorNamingIt)
    }
    ++files;
    ASSERT_EQ(scene.face_tallies.size(), 1u);
    const FaceTally& tally = scene.face_tallies[0];
    EXPECT_EQ(tally.kept, scene.triangles.size()) << entry.path();
    EXPECT_GE(tally.declared, tally.kept) << entry.path();
    if (tally.declared > tally.kept) {
      ++with_points_or_lines;
      EXPECT_EQ(scene.warnings.size(), 1u) << entry.path();
    }
  }
  EXPECT_GE(files, 4u);
  const fs::path lossy = root / "glTF2" / "IndexOutOfRange" / "IndexOutOfRange.gltf";
  const SceneDesc scene = read_imported_mesh(lossy);
  ASSERT_EQ(scene.face_tallies.size(), 1u);
  EXPECT_EQ(scene.face_tallies[0].declared, 12u);
  EXPECT_EQ(scene.face_tallies[0].kept, 11u);
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_EQ(scene.warnings[0], lossy.string() + ": warning: expected the 12 triangles the file declares, found 11 "
                                                "read by Assimp; the others are not drawn");
  EXPECT_THROW(read_imported_mesh(lossy, kDefaultCreaseAngleDegrees, true), ParseError);
  RecordProperty("primitive_mode_files", std::to_string(files));
  RecordProperty("with_points_or_lines", std::to_string(with_points_or_lines));
}

TEST(MeshImportPublicModels, ReadAsTheirFormatsDescribeThem) {
  const fs::path root = public_models();
  if (!fs::is_directory(root)) {
    GTEST_SKIP() << root << " not found: apt-get install assimp-testmodels, or set QUIVER_ASSIMP_MODELS_DIR";
  }
  // The Khronos textured box as .glb (image in the binary chunk), .gltf
  // with a .bin and a .png beside it, and .gltf with data URIs: the same
  // 12 triangles and the same texels.
  const SceneDesc binary = load_scene(root / "glTF2" / "BoxTextured-glTF-Binary" / "BoxTextured.glb");
  const SceneDesc beside = load_scene(root / "glTF2" / "BoxTextured-glTF" / "BoxTextured.gltf");
  const SceneDesc embedded = load_scene(root / "glTF2" / "BoxTextured-glTF-Embedded" / "BoxTextured.gltf");
  ASSERT_EQ(binary.triangles.size(), 12u);
  ASSERT_EQ(binary.textures.size(), 1u);
  EXPECT_FALSE(binary.textures[0].rgb.empty());
  for (const SceneDesc* other : {&beside, &embedded}) {
    expect_same_triangles(binary, *other, 0.f);
    ASSERT_EQ(other->textures.size(), 1u);
    EXPECT_EQ(other->textures[0].rgb, binary.textures[0].rgb);
  }
  EXPECT_FALSE(beside.textures[0].path.empty());  // CesiumLogoFlat.png beside it
  EXPECT_TRUE(embedded.textures[0].path.empty());

  // The same spider as ASCII and binary STL.
  const SceneDesc ascii_spider = read_imported_mesh(root / "STL" / "Spider_ascii.stl");
  const SceneDesc binary_spider = read_imported_mesh(root / "STL" / "Spider_binary.stl");
  EXPECT_GT(ascii_spider.triangles.size(), 1000u);
  EXPECT_EQ(ascii_spider.triangles.size(), binary_spider.triangles.size());

  // Blender 2.47's PLY header line without "comment": a warning, read as Assimp reads it.
  const SceneDesc wuson = read_imported_mesh(root / "PLY" / "Wuson.ply");
  EXPECT_FALSE(wuson.triangles.empty());
  ASSERT_EQ(wuson.warnings.size(), 1u);
  EXPECT_NE(wuson.warnings[0].find("Wuson.ply:3:1: warning: expected a PLY header line"), std::string::npos)
      << wuson.warnings[0];
  EXPECT_THROW(read_imported_mesh(root / "PLY" / "Wuson.ply", kDefaultCreaseAngleDegrees, true), ParseError);

  // Broken on purpose, each refused where it is broken.
  const std::pair<fs::path, std::string> broken[] = {
      // 70051 vertices of 31 bytes are 69 bytes more than the file holds.
      {root / "PLY" / "pond.0.ply", ":3:16: expected an element count that the 2171512 bytes after the header"},
      {root / "glTF2" / "BoxWithInfinites-glTF-Binary" / "BoxWithInfinites.glb", ": expected finite vertex positions"},
      {root / "glTF2" / "MissingBin" / "BoxTextured.gltf", ": expected buffers[0]'s file 'BoxTextured0.bin'"},
      {root / "glTF2" / "draco" / "2CylinderEngine.gltf",
       ": uses KHR_draco_mesh_compression, which quiver does not read"},
      {root / "glTF2" / "IncorrectVertexArrays" / "Cube.gltf",
       ": expected bufferViews[2].byteLength to be at most the 10 bytes of buffers[0] after its byteOffset 504"},
      {root / "glTF2" / "RecursiveNodes" / "RecursiveNodes.gltf",
       ": expected nodes that form trees, found nodes[0] among its own descendants"},
      {root / "glTF" / "BoxTextured-glTF-Binary" / "BoxTextured.glb", ": byte 4: expected GLB version 2, found 1"},
  };
  for (const auto& [path, message] : broken) {
    const std::string what = import_error(path);
    EXPECT_EQ(what.rfind(path.string() + message, 0), 0u) << what;
  }
  // glTF 1.0 names its buffers (an object): read too.
  EXPECT_FALSE(load_scene(root / "glTF" / "CesiumMilkTruck" / "CesiumMilkTruck.gltf").triangles.empty());
}

TEST(MeshImport, TheSceneLoaderReadsEveryFormatByExtension) {
  for (const char* name : {"roof.ply", "roof.stl", "triangle.gltf"}) {
    const SceneDesc scene = load_scene(kMeshes / name);
    EXPECT_FALSE(scene.triangles.empty()) << name;
    EXPECT_EQ(scene.source_files.front(), (kMeshes / name).string());
  }
}

}  // namespace
}  // namespace quiver
