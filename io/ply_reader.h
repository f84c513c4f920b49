// PLY reader: ASCII, binary_little_endian and binary_big_endian in one pass
// over the file's bytes, into an indexed triangle mesh that
// io/mesh_import.h turns into the scene (its smooth normals are OBJ's).
// Read: the `vertex` element's x, y, z (any scalar type), nx, ny, nz and
// texture coordinates (u v, s t or texture_u texture_v) when present;
// `face` lists (`vertex_indices` or `vertex_index`) as polygons,
// triangulated (quads from their concave corner and in Assimp 5.2's corner
// order, larger polygons as OBJ's faces: io/face_triangulation.h), with their `texcoord`
// lists (a vertex of its own for each such corner); `tristrips` lists, where
// -1 restarts a strip and every second triangle turns the other way.
// Rules: every element count and list length is bounded by the bytes that
// follow it before anything is allocated; ASCII holds one element per line,
// each value a number of its property's type (an index a whole number);
// coordinates, normals and texture coordinates are finite and within
// +-3.4e38 (OBJ's bound); an index outside the vertex element is an error.
// Faces of fewer than three corners and elements of geometry quiver cannot
// draw (`edge`) are dropped with a warning; strip triangles with a repeated
// index (strips' joints) are dropped and counted. Errors name
// file:line:column (header, ASCII data) or "file: byte N: expected X,
// found Y" (binary data). Format rules and bounds: io/README.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "io/obj_reader.h"
#include "io/reader_warnings.h"

namespace quiver {

struct PlyMesh {
  std::vector<float> positions;            // x y z of each vertex
  std::vector<float> normals;              // nx ny nz of each vertex; empty when the file has none
  std::vector<float> uvs;                  // u v of each vertex; empty when the file has none
  std::vector<std::uint32_t> triangles;    // three vertex indices each, front face counter-clockwise
  std::size_t point_cloud_vertices = 0;    // the vertices of a file without face or tristrips elements
  std::size_t degenerate_strip_triangles = 0;
  std::uint64_t strip_triangles = 0;  // kept, from tristrips
  // Faces declared (face elements, strip triangles other than degenerate
  // joins, edges) and kept (faces of 3 or more vertices, strip triangles).
  std::uint64_t faces_declared = 0, faces_kept = 0;
  std::optional<SceneDesc::StatedUp> stated_up;  // io/creator_up_axis.h, from a header comment
};

// `bytes` is the whole file, `file` its name in messages. At most
// kMaxObjVertices vertices and triangle_budget triangles. A header line
// that is none of PLY's (Blender 2.4 wrote "Created by ..." without
// "comment") is a warning and skipped, as are short faces and unreadable
// geometry; strict `warnings` make each an error. Throws ParseError.
PlyMesh read_ply(std::string_view bytes, std::string_view file, ReaderWarnings& warnings,
                 std::size_t triangle_budget = kMaxObjTriangles);

}  // namespace quiver
