// libFuzzer target for quiver's PLY reader (io/ply_reader.h) and the
// structural checks run before Assimp reads an STL or glTF file
// (io/mesh_file_check.h). The input's first byte picks the reader (0 PLY,
// 1 STL, 2 glTF text, 3 GLB; modulo 4), the rest is the file's bytes; glTF
// buffer URIs resolve in tests/data/mesh. $QUIVER_FUZZ_MESH_KIND (0 to 3),
// when set, picks the reader instead, the first byte still skipped, so that
// a run can fuzz one format (run.sh's ply, gltf and glb).
// quiver::ParseError is the only accepted failure; any other exception, a
// sanitizer report or a broken invariant is a finding.
//
// Invariants on success: a PLY's vertices and triangles are within the OBJ
// bounds (kMaxObjVertices, kMaxObjTriangles), its normals and texture
// coordinates are per vertex, every index names a vertex, and
// io/ply_writer.h writes it as bytes that read back to the same bits; a binary
// STL's triangle count is what its size says; a glTF's placed triangles and
// nodes are within the budget and kMaxGltfNodePlacements.
// Invariants on ParseError: file() is the input's name; an error with a
// line points into the input as the text readers' do (PLY's header and
// ASCII data, glTF's JSON), one without reads "name: ...".
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>

#include "io/mesh_file_check.h"
#include "io/obj_reader.h"
#include "io/parse_error.h"
#include "io/ply_reader.h"
#include "io/ply_writer.h"
#include "tests/fuzz/scene_invariants.h"

namespace {

constexpr std::string_view kNames[] = {"fuzz.ply", "fuzz.stl", "fuzz.gltf", "fuzz.glb"};
constexpr std::size_t kMaxBytes = std::size_t{1} << 30;

// The check $QUIVER_FUZZ_MESH_KIND forces, or -1.
int forced_kind() {
  const char* kind = std::getenv("QUIVER_FUZZ_MESH_KIND");
  return kind != nullptr && kind[0] >= '0' && kind[0] <= '3' && kind[1] == '\0' ? kind[0] - '0' : -1;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const int forced = forced_kind();
  const std::size_t kind = forced >= 0 ? static_cast<std::size_t>(forced) : data[0] % 4;
  const std::string_view bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
  const std::string_view name = kNames[kind];
  using quiver::fuzz::check;
  try {
    switch (kind) {
      case 0: {
        quiver::ReaderWarnings warnings(false);
        const quiver::PlyMesh mesh = quiver::read_ply(bytes, name, warnings);
        const std::size_t vertices = mesh.positions.size() / 3;
        check(mesh.positions.size() % 3 == 0 && vertices <= quiver::kMaxObjVertices);
        check(mesh.triangles.size() % 3 == 0 && mesh.triangles.size() / 3 <= quiver::kMaxObjTriangles);
        check(mesh.normals.empty() || mesh.normals.size() == 3 * vertices);
        check(mesh.uvs.empty() || mesh.uvs.size() == 2 * vertices);
        for (std::uint32_t index : mesh.triangles) check(index < vertices);
        // What io/ply_writer.h writes of it reads back to the same bits.
        const quiver::PlyMesh back = quiver::read_ply(quiver::binary_ply(mesh), name, warnings);
        const auto same_bits = [](const std::vector<float>& a, const std::vector<float>& b) {
          return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
        };
        check(same_bits(back.positions, mesh.positions) && same_bits(back.normals, mesh.normals) &&
              same_bits(back.uvs, mesh.uvs) && back.triangles == mesh.triangles);
        break;
      }
      case 1: {
        const quiver::MeshFileCounts counts = quiver::check_stl(bytes, name);
        check(!counts.stl_binary || 84 + 50 * counts.triangles == bytes.size());
        if (counts.stl_binary) check(quiver::binary_stl_corners(bytes, counts.triangles).size() == 9 * counts.triangles);
        break;
      }
      default: {
        const quiver::GltfContents contents =
            quiver::check_gltf(bytes, name, QUIVER_FUZZ_FILES_DIR, quiver::PathRule{}.for_folder(QUIVER_FUZZ_FILES_DIR),
                               kind == 3, kMaxBytes, quiver::kMaxObjTriangles);
        check(contents.placed_triangles <= quiver::kMaxObjTriangles &&
              contents.node_placements <= quiver::kMaxGltfNodePlacements);
      }
    }
  } catch (const quiver::ParseError& error) {
    check(error.file() == name);
    if (error.line() == 0) {
      check(std::string_view(error.what()).substr(0, name.size() + 2) == std::string(name) + ": ");
    } else if (kind != 3) {
      quiver::fuzz::check_error_position(error, bytes, false);
    }
  }
  return 0;
}
