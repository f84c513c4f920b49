// Appends a mesh file (OBJ, PLY, glTF or STL, by its extension) to a scene
// under a transform: how a TOML scene's [[meshes]] entries are read.
#pragma once

#include <array>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>

#include "geometry/vertex_normals.h"
#include "io/path_rule.h"
#include "scene/scene_desc.h"

namespace quiver {

// true for the extensions append_mesh reads (".obj", ".ply", ".gltf",
// ".glb", ".stl"; lower case, with the dot).
bool is_mesh_extension(std::string_view extension);

// Triangles a scene holding `stored` can still take (kMaxObjTriangles in all).
std::size_t triangles_left(std::size_t stored);

// Reads the mesh file at `path` (read_obj_scene or read_imported_mesh) and
// appends its triangles to `scene`, transformed by `transform` (a 4x4
// matrix, column-major: element (row r, column c) at [4 * c + r]) for
// positions and by its inverse transpose for normals; a transform that
// mirrors (negative determinant) reverses each triangle's winding. With
// material_override (an index into scene.materials) every triangle uses it
// and the file's materials are not added; otherwise the mesh's materials
// and textures are appended. Smooth normals (crease_angle_degrees, as the
// readers) are computed before the transform, on the mesh as written; its
// warnings are appended to scene.warnings. Throws ParseError, also when
// scene.triangles would exceed kMaxObjTriangles or a transformed vertex is
// not finite, and std::invalid_argument for a singular or non-finite
// transform, an override that is not a material index or a path that names
// no mesh format; `scene` is then unchanged. The files the mesh names keep
// `paths` (io/path_rule.h).
void append_mesh(const std::filesystem::path& path, const std::array<float, 16>& transform,
                 std::optional<std::size_t> material_override, SceneDesc& scene,
                 double crease_angle_degrees = kDefaultCreaseAngleDegrees, bool strict = false,
                 const PathRule& paths = {});

// Mesh files held in memory by the name a scene gives them: their bytes.
using MeshBytes = std::map<std::string, std::string, std::less<>>;

// append_mesh for a PLY or STL held in memory (io/mesh_import.h's
// read_mesh_bytes): `name` is the file it stands for in messages, and is not
// listed in scene.source_files, as no file was read. Throws as append_mesh,
// and std::invalid_argument for another format.
void append_mesh_bytes(std::string_view bytes, const std::filesystem::path& name,
                       const std::array<float, 16>& transform, std::optional<std::size_t> material_override,
                       SceneDesc& scene, double crease_angle_degrees = kDefaultCreaseAngleDegrees,
                       bool strict = false);

}  // namespace quiver
