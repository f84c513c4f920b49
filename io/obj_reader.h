// Reader for Wavefront OBJ meshes and their MTL material libraries: one
// strict pass over the text (its plain lines parsed ahead on every thread)
// that reports bad input as ParseError with file:line:column (numbers,
// NaN/Inf, index ranges, counts) and builds the scene as it reads. Faces
// become triangles (quads and convex n-gons as fans, concave n-gons by ear
// clipping), with per-vertex normals and uvs when the face gives them;
// faces without normals get angle-weighted vertex normals with a crease
// angle (geometry/vertex_normals.h). The format rules, the MTL mapping and
// the bounds are in io/README.md.
#pragma once

#include <array>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "geometry/vertex_normals.h"
#include "io/path_rule.h"
#include "scene/scene_desc.h"

namespace quiver {

// Largest OBJ input, and largest total of the MTL libraries it names, in bytes.
inline constexpr std::size_t kMaxObjBytes = std::size_t{1} << 30;
inline constexpr std::size_t kMaxMtlBytes = std::size_t{64} << 20;
// Most distinct MTL libraries one OBJ may name.
inline constexpr std::size_t kMaxMtlLibraries = 64;
// Most `v`, `vt` and `vn` statements (each kind), and most triangles after
// triangulation; the triangle bound also caps a whole scene's triangles
// when meshes are appended to it (io/mesh_append.h), whatever their format.
inline constexpr std::size_t kMaxObjVertices = std::size_t{1} << 24;
inline constexpr std::size_t kMaxObjTriangles = std::size_t{1} << 24;
// Largest magnitude of a mesh coordinate: a round bound just below FLT_MAX
// (3.4028235e38), so that nothing downstream (a bounding box's extent, the
// auto camera) is within rounding of overflow. The OBJ reader's number
// bound; imported meshes' positions keep it too (io/mesh_import.h).
inline constexpr float kLargestMeshCoordinate = 3.4e38f;
// Most corners of `f`, `l` and `p` statements together.
inline constexpr std::size_t kMaxObjCorners = std::size_t{1} << 26;
// Most vertices of one face: this reader's bound, far above what meshes
// use, so that no single face makes ear clipping (cubic at worst) slow.
inline constexpr std::size_t kMaxObjFaceVertices = 255;

// An MTL library as the OBJ names it: its text, the name used in error
// messages, the folder its texture paths are relative to, and the rule
// they must keep (io/path_rule.h; by default the library's folder).
struct MtlLibrary {
  std::string text;
  std::string file_name;
  std::filesystem::path directory;
  PathRule paths;
};

// Finds the library an `mtllib` statement names; nullopt when there is none
// (the reader then reports the name's position). May throw ParseError for a
// library that exists but cannot be read.
using MtlLookup = std::function<std::optional<MtlLibrary>(std::string_view name)>;

// Reads an OBJ file and the MTL libraries it names (relative to its folder).
// Every face gets its MTL material, or the default MaterialDesc when it has
// none. Forgiving unless `strict`: a missing MTL library or map_Kd image,
// a `usemtl` of an undefined material and a trailing "# comment" are
// warnings in SceneDesc::warnings (io/reader_warnings.h; the default
// material, no texture, the statement ending before the '#'); strict, each
// is a ParseError. Faces without `vn` get smooth normals: angle-weighted over the
// faces that share each `v` index and whose normals lie within
// crease_angle_degrees of the face's own ([0, 180]; 0 leaves them faceted).
// Faces with `vn` keep theirs. At most triangle_budget triangles. Libraries
// and images outside `paths` are errors (io/path_rule.h). Throws
// ParseError, and std::invalid_argument for a crease angle outside [0, 180].
SceneDesc read_obj_scene(const std::filesystem::path& path,
                         double crease_angle_degrees = kDefaultCreaseAngleDegrees, bool strict = false,
                         std::size_t triangle_budget = kMaxObjTriangles, const PathRule& paths = {});

// Parses OBJ text; file_name labels error messages; `mtllib` names go
// through find_library.
SceneDesc parse_obj_scene(std::string_view text, std::string_view file_name, const MtlLookup& find_library,
                          double crease_angle_degrees = kDefaultCreaseAngleDegrees, bool strict = false);

}  // namespace quiver
