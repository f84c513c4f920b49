// Reader for PLY (quiver's own reader, io/ply_reader.h), glTF 2.0 (.gltf,
// .glb) and STL meshes (through Assimp: the quiver_assimp module, loaded on
// first use, io/assimp_loader.h). Before Assimp sees a file its structure
// is checked (io/mesh_file_check.h), so memory stays bounded by the file's
// size and the errors name file:line:column or the byte; Assimp's own
// errors read "file: Assimp: message". The result is a SceneDesc of triangles in world
// space (each mesh placed by every node that names it, the winding kept
// front-facing under a mirror; points and lines dropped with a warning). Normals as the file gives them; PLY faces without normals and
// every STL face (whose normals are per facet) get smooth normals with the
// crease angle, over vertices welded by exact position; a glTF mesh without
// normals stays faceted, as its specification asks. Materials: glTF's base
// colour, its texture (a file beside the mesh, or an image embedded in the
// GLB or a data URI, kept encoded in TextureDesc::encoded for
// io/texture_image.h), doubleSided, and KHR_materials_transmission and
// _ior as refraction; PLY and STL faces get the default material. The format rules and bounds are in io/README.md.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string_view>

#include "geometry/vertex_normals.h"
#include "io/obj_reader.h"
#include "io/path_rule.h"
#include "scene/scene_desc.h"

namespace quiver {

// Largest mesh file, with a glTF's buffer files, in bytes (OBJ's bound).
inline constexpr std::size_t kMaxImportedMeshBytes = kMaxObjBytes;

// true for ".ply", ".gltf", ".glb" and ".stl" (lower case, with the dot).
bool is_imported_mesh_extension(std::string_view extension);

// Reads the mesh at path (its extension names the format). At most
// triangle_budget triangles (kMaxObjTriangles in all when meshes are
// appended), counted for glTF before Assimp runs; vertex positions finite
// and within +-kLargestMeshCoordinate. A glTF's buffer and image files are
// listed in the result's source_files (the file itself is not), and files
// outside `paths` are errors (io/path_rule.h). Strict: what is otherwise a
// warning is a ParseError. Throws ParseError, also when the Assimp module
// cannot be loaded (glTF, STL), and
// std::invalid_argument for a crease angle outside [0, 180].
SceneDesc read_imported_mesh(const std::filesystem::path& path,
                             double crease_angle_degrees = kDefaultCreaseAngleDegrees, bool strict = false,
                             std::size_t triangle_budget = kMaxObjTriangles, const PathRule& paths = {});

// A PLY or STL mesh from its bytes, as read_imported_mesh reads the file
// `path` names when it holds them (path gives the format and the name in
// messages; nothing is read from disk). At most kMaxImportedMeshBytes.
// Throws as read_imported_mesh, and std::invalid_argument for glTF, whose
// buffers and images lie in other files.
SceneDesc read_mesh_bytes(std::string_view bytes, const std::filesystem::path& path,
                          double crease_angle_degrees = kDefaultCreaseAngleDegrees, bool strict = false,
                          std::size_t triangle_budget = kMaxObjTriangles);

}  // namespace quiver
