// Structural checks of a parsed glTF document (2.0, or 1.0 whose
// collections are objects keyed by id) before Assimp reads it, in one pass
// over the JSON: every bufferView within its buffer, every accessor
// (sparse parts too) within its bufferView, with checked arithmetic; the
// references meshes, nodes, scenes and images make; extensions whose data
// quiver does not bound refused; and the node graph (no cycles, bounded
// depth) with the meshes' placements counted without expanding it, so that
// the triangles and nodes Assimp would make are bounded before it runs.
// Errors read "file: expected PATH ..., found ..." with PATH the JSON path
// (accessors[3].sparse.indices.byteOffset). The rules: io/README.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "io/gltf_lights.h"
#include "io/obj_reader.h"
#include "io/path_rule.h"

namespace quiver {

// Deepest node chain (a node, its child, ...): Assimp walks the chain by
// recursion, and far deeper chains overflow its stack.
inline constexpr std::size_t kMaxGltfNodeDepth = 256;
// Nodes Assimp makes once a node placed by several parents is copied under
// each: every one holds a 1 KB name.
inline constexpr std::uint64_t kMaxGltfNodePlacements = std::uint64_t{1} << 16;
// Elements of one accessor: the indices of the triangle bound's triangles.
inline constexpr std::uint64_t kMaxGltfAccessorCount = 3 * std::uint64_t{kMaxObjTriangles};
// Vertices of triangle primitives copied per placement: as many as the
// triangle bound's triangles have when no vertex is shared.
inline constexpr std::uint64_t kMaxGltfPlacedVertices = 3 * std::uint64_t{kMaxObjTriangles};
// Bytes Assimp decodes from accessors (4 per component), counted once per
// reference from a primitive, morph target, skin or animation sampler, and
// the bytes of images' bufferViews, once per image.
inline constexpr std::uint64_t kMaxGltfDecodedBytes = std::uint64_t{1} << 30;

// Values in a glTF's JSON (each number, string, array and object), counted
// as it is parsed: nlohmann/json takes 16 bytes to over 100 per value.
inline constexpr std::size_t kMaxGltfJsonValues = std::size_t{1} << 22;

// What the checks found that the caller needs.
struct GltfContents {
  std::uint64_t placed_triangles = 0;  // each mesh's triangles times its placements
  std::uint64_t node_placements = 0;   // nodes once placed under every parent
  // The files the glTF names by URI that exist (relative to its folder):
  // check_gltf_contents adds the images'; check_gltf (io/mesh_file_check.h)
  // puts the buffers' before them.
  std::vector<std::filesystem::path> files;
  // Its camera (io/gltf_camera.h), filled by check_gltf (io/mesh_file_check.h).
  std::optional<CameraDesc> camera;
  std::string unused_camera;  // a camera a node names that is not used, and why
  // Its punctual lights (io/gltf_lights.h), filled by check_gltf.
  GltfLights lights;
};

// `document` is the parsed glTF whose buffers (byteLength) have been checked
// against their data; `directory` the folder URIs are relative to, and an
// image URI outside `paths` is an error (io/path_rule.h). Throws
// ParseError naming `file`, also when the placed triangles exceed
// triangle_budget.
GltfContents check_gltf_contents(const nlohmann::json& document, std::string_view file,
                                 const std::filesystem::path& directory, const PathRule& paths,
                                 std::size_t triangle_budget);

}  // namespace quiver
