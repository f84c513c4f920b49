#include "io/ply_writer.h"

#include <bit>
#include <cstring>
#include <stdexcept>

namespace quiver {
namespace {

static_assert(std::endian::native == std::endian::little, "binary_ply copies little-endian words as they lie");

void check(const PlyMesh& mesh, std::size_t vertices) {
  if (mesh.positions.size() % 3 != 0) throw std::invalid_argument("binary_ply: positions are not x, y, z triples");
  if (!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size()) {
    throw std::invalid_argument("binary_ply: not one normal per vertex");
  }
  if (!mesh.uvs.empty() && mesh.uvs.size() != 2 * vertices) {
    throw std::invalid_argument("binary_ply: not one texture coordinate per vertex");
  }
  if (mesh.triangles.size() % 3 != 0) throw std::invalid_argument("binary_ply: triangles are not index triples");
  if (vertices > kMaxObjVertices || mesh.triangles.size() / 3 > kMaxObjTriangles) {
    throw std::invalid_argument("binary_ply: more vertices or triangles than the PLY reader accepts");
  }
  for (const std::uint32_t index : mesh.triangles) {
    if (index >= vertices) throw std::invalid_argument("binary_ply: an index names no vertex");
  }
}

template <class T>
char* put(char* out, const T& value) {
  std::memcpy(out, &value, sizeof value);
  return out + sizeof value;
}

}  // namespace

std::string binary_ply(const PlyMesh& mesh) {
  const std::size_t vertices = mesh.positions.size() / 3;
  check(mesh, vertices);
  const bool normals = !mesh.normals.empty(), uvs = !mesh.uvs.empty();
  std::string header = "ply\nformat binary_little_endian 1.0\ncomment written by quiver\nelement vertex " +
                       std::to_string(vertices) + "\nproperty float x\nproperty float y\nproperty float z\n";
  if (normals) header += "property float nx\nproperty float ny\nproperty float nz\n";
  if (uvs) header += "property float u\nproperty float v\n";
  header += "element face " + std::to_string(mesh.triangles.size() / 3) +
            "\nproperty list uchar uint vertex_indices\nend_header\n";
  const std::size_t vertex_bytes = 4 * (3 + (normals ? 3 : 0) + (uvs ? 2 : 0));
  const std::size_t face_bytes = 1 + 3 * 4;
  std::string bytes(header.size() + vertices * vertex_bytes + mesh.triangles.size() / 3 * face_bytes, '\0');
  char* out = std::copy(header.begin(), header.end(), bytes.data());
  for (std::size_t v = 0; v < vertices; ++v) {
    for (std::size_t c = 0; c < 3; ++c) out = put(out, mesh.positions[3 * v + c]);
    for (std::size_t c = 0; normals && c < 3; ++c) out = put(out, mesh.normals[3 * v + c]);
    for (std::size_t c = 0; uvs && c < 2; ++c) out = put(out, mesh.uvs[2 * v + c]);
  }
  for (std::size_t f = 0; f < mesh.triangles.size(); f += 3) {
    out = put(out, std::uint8_t{3});
    for (std::size_t c = 0; c < 3; ++c) out = put(out, mesh.triangles[f + c]);
  }
  return bytes;
}

}  // namespace quiver
