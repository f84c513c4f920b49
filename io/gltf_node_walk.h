// A glTF 2.0 document's nodes walked depth-first with their world
// transforms, for the readers of what nodes place (io/gltf_camera.h,
// io/gltf_lights.h), after io/gltf_check.h has checked that the nodes form
// trees. The roots are those Assimp reads: "scene"'s nodes, else every
// scene's in turn, else every node no other names (as io/gltf_check.cpp
// counts them), in their order. A node's world transform is its ancestors'
// local transforms times its own: its "matrix", else translation x rotation
// (a unit quaternion x, y, z, w) x scale.
#pragma once

#include <array>
#include <functional>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <string_view>

#include "io/parse_error.h"
#include "simd/vec3.h"

namespace quiver {

using GltfMatrix = std::array<double, 16>;  // column-major, as glTF's "matrix"

// visit(node, its JSON path "nodes[i]", its world transform) for each node
// depth-first, until visit returns false. Throws ParseError naming file and
// the JSON path of a transform value that is not a finite number.
void walk_gltf_nodes(const nlohmann::json& document, std::string_view file,
                     const std::function<bool(const nlohmann::json& node, const std::string& path,
                                              const GltfMatrix& world)>& visit);

// world x (x, y, z, w): a point for w = 1, a direction for w = 0.
Vec3<float> gltf_transformed(const GltfMatrix& world, double x, double y, double z, double w);

// The error for the value at a JSON path: "expected PATH to be EXPECTED".
ParseError gltf_value_error(std::string_view file, const std::string& path, std::string_view expected);

}  // namespace quiver
