// PLY writer: an indexed triangle mesh (io/ply_reader.h's PlyMesh: positions,
// optional per-vertex normals and texture coordinates, triangles) as
// binary_little_endian 1.0, the layout io/ply_reader.h reads back to the same
// floats and indices: a `vertex` element of float x y z [nx ny nz] [u v] and
// a `face` element of uchar-counted uint `vertex_indices` lists of three.
// How a Python scene's array meshes become files the CLI reads.
#pragma once

#include <string>

#include "io/ply_reader.h"

namespace quiver {

// The file's bytes. Throws std::invalid_argument when normals or uvs are
// present but not one per vertex, positions are not whole triples, an index
// names no vertex, or the counts exceed the reader's bounds (kMaxObjVertices
// vertices, kMaxObjTriangles triangles).
std::string binary_ply(const PlyMesh& mesh);

}  // namespace quiver
