// Structural checks of STL and glTF/GLB files before Assimp reads them
// (io/mesh_import.h), so that no count in a file makes the importer
// allocate more than the file's bytes can back: a binary STL's triangle
// count against the file's size, a GLB's length and chunks, and every glTF
// buffer's byteLength against the file or data URI that holds it, then the
// rest of the glTF (io/gltf_check.h). PLY is read by quiver itself
// (io/ply_reader.h). Errors in text name file:line:column; in binary data,
// "file: byte N: expected X, found Y".
#pragma once

#include <cstddef>
#include <filesystem>
#include <string_view>
#include <vector>

#include "io/gltf_check.h"
#include "io/path_rule.h"

namespace quiver {

// What the file's header declares, for the caller's bounds.
struct MeshFileCounts {
  std::size_t triangles = 0;  // 0 when unknown
  bool stl_binary = false;
};

// `bytes` is the whole file, `file` its name in messages. Throws ParseError.
MeshFileCounts check_stl(std::string_view bytes, std::string_view file);
// The corners of a binary STL that check_stl accepted (counts.stl_binary):
// x y z of each triangle's three vertices in file order, 9 floats a
// triangle, read from their little-endian bytes (the facet normals and
// attribute words skipped). quiver reads binary STL itself; ASCII STL goes
// to Assimp.
std::vector<float> binary_stl_corners(std::string_view bytes, std::size_t triangles);
// glTF: the JSON text of a .gltf, or the bytes of a .glb; buffers named by
// URI are looked for relative to `directory` (outside `paths`, an error:
// io/path_rule.h), and their sizes added up with the file's against
// max_total_bytes; then the document's contents (io/gltf_check.h), its
// placed triangles against triangle_budget.
GltfContents check_gltf(std::string_view bytes, std::string_view file, const std::filesystem::path& directory,
                        const PathRule& paths, bool binary, std::size_t max_total_bytes,
                        std::size_t triangle_budget);

}  // namespace quiver
