// Tests of io/ply_writer.h: what binary_ply writes, io/ply_reader.h reads
// back to the same floats and indices; malformed meshes are refused.
#include "io/ply_writer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include "io/mesh_import.h"
#include "io/parse_error.h"

namespace quiver {
namespace {

// Two triangles of a quad with awkward floats (subnormal, negative zero, the largest).
PlyMesh quad() {
  PlyMesh mesh;
  mesh.positions = {0.f, -0.f, 1e-40f, 1.f, 0.1f, 0.f, 1.f, 1.f, std::numeric_limits<float>::max() / 4, 0.f, 1.f, 0.f};
  mesh.triangles = {0, 1, 2, 0, 2, 3};
  return mesh;
}

void expect_bits(const std::vector<float>& a, const std::vector<float>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(std::signbit(a[k]), std::signbit(b[k])) << k;
    EXPECT_EQ(a[k], b[k]) << k;
  }
}

PlyMesh read_back(const std::string& bytes) {
  ReaderWarnings warnings(true);
  return read_ply(bytes, "written.ply", warnings);
}

TEST(PlyWriter, PositionsNormalsUvsAndIndicesReadBackExactly) {
  for (const bool normals : {false, true}) {
    for (const bool uvs : {false, true}) {
      PlyMesh mesh = quad();
      if (normals) mesh.normals = {0.f, 0.f, 1.f, 0.f, 0.6f, 0.8f, 0.f, 0.f, -1.f, 1.f, 0.f, 0.f};
      if (uvs) mesh.uvs = {0.f, 0.f, 1.f, 0.f, 1.f, 1.f, 0.25f, 1.f};
      const PlyMesh back = read_back(binary_ply(mesh));
      expect_bits(back.positions, mesh.positions);
      expect_bits(back.normals, mesh.normals);
      expect_bits(back.uvs, mesh.uvs);
      EXPECT_EQ(back.triangles, mesh.triangles);
      EXPECT_EQ(back.faces_declared, 2u);
      EXPECT_EQ(back.faces_kept, 2u);
    }
  }
}

TEST(PlyWriter, AMeshWithoutTrianglesKeepsItsVerticesAndAnEmptyFaceElement) {
  PlyMesh mesh = quad();
  mesh.triangles.clear();
  const PlyMesh back = read_back(binary_ply(mesh));
  expect_bits(back.positions, mesh.positions);
  EXPECT_TRUE(back.triangles.empty());
  EXPECT_EQ(back.faces_declared, 0u);
}

TEST(PlyWriter, MalformedMeshesAreRefused) {
  PlyMesh mesh = quad();
  mesh.triangles[5] = 4;  // one past the last vertex
  EXPECT_THROW(binary_ply(mesh), std::invalid_argument);
  mesh = quad();
  mesh.normals = {0.f, 0.f, 1.f};
  EXPECT_THROW(binary_ply(mesh), std::invalid_argument);
  mesh = quad();
  mesh.uvs = {0.f, 0.f, 1.f, 0.f, 1.f, 1.f};
  EXPECT_THROW(binary_ply(mesh), std::invalid_argument);
  mesh = quad();
  mesh.positions.pop_back();
  EXPECT_THROW(binary_ply(mesh), std::invalid_argument);
  mesh = quad();
  mesh.triangles.pop_back();
  EXPECT_THROW(binary_ply(mesh), std::invalid_argument);
}

// The error binary_ply gives `mesh` ("" when it writes it).
std::string write_error(const PlyMesh& mesh) {
  try {
    binary_ply(mesh);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

// At the reader's bounds a mesh passes them (and is refused only for an
// index past its vertices); one vertex or triangle more, for its counts.
TEST(PlyWriter, CountsAtTheReadersBoundsPassThemAndOneMoreDoesNot) {
  const std::string past_bounds = "more vertices or triangles than the PLY reader accepts";
  PlyMesh mesh;
  mesh.positions.assign(3 * kMaxObjVertices, 0.f);
  mesh.triangles = {0, 1, std::uint32_t(kMaxObjVertices)};
  EXPECT_NE(write_error(mesh).find("an index names no vertex"), std::string::npos) << write_error(mesh);
  mesh.positions.resize(3 * (kMaxObjVertices + 1));
  EXPECT_NE(write_error(mesh).find(past_bounds), std::string::npos) << write_error(mesh);
  mesh.positions.assign(3 * 3, 0.f);
  mesh.triangles.assign(3 * kMaxObjTriangles, 0);
  mesh.triangles.back() = 3;
  EXPECT_NE(write_error(mesh).find("an index names no vertex"), std::string::npos) << write_error(mesh);
  mesh.triangles.resize(3 * (kMaxObjTriangles + 1));
  EXPECT_NE(write_error(mesh).find(past_bounds), std::string::npos) << write_error(mesh);
}

TEST(MeshBytes, APlyFromBytesIsTheSceneOfItsFileAndGltfIsRefused) {
  const std::string bytes = binary_ply(quad());
  const SceneDesc scene = read_mesh_bytes(bytes, "held.ply", 0.0);
  ASSERT_EQ(scene.triangles.size(), 2u);
  EXPECT_EQ(scene.triangles[1].triangle.p[1].y, 1.f);
  EXPECT_TRUE(scene.source_files.empty());
  EXPECT_THROW(read_mesh_bytes(bytes, "held.gltf"), std::invalid_argument);
  EXPECT_THROW(read_mesh_bytes(bytes, "held.obj"), std::invalid_argument);
  EXPECT_THROW(read_mesh_bytes(bytes.substr(0, bytes.size() - 1), "held.ply"), ParseError);
  EXPECT_THROW(read_mesh_bytes(bytes, "held.ply", 0.0, false, 1), ParseError);  // over the triangle budget
}

}  // namespace
}  // namespace quiver
