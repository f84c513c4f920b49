// A glTF 2.0 file's camera, read from its JSON after io/gltf_check.h has
// checked the document (nodes form trees): the first node, depth-first from
// the roots (io/gltf_node_walk.h), that names a perspective camera. The
// camera looks down the node's -z with +y up, placed by the node's world
// transform. glTF's yfov spans the image's height edge to edge; quiver's
// angle spans the outermost pixel centres of the longer side, of an image
// kDefaultImageSide wide or tall as aspectRatio says (square without one).
// An orthographic camera is not used (quiver's camera is a pinhole): the
// result says so, for a warning.
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "scene/scene_desc.h"

namespace quiver {

struct GltfCamera {
  std::optional<CameraDesc> camera;
  std::string unused;  // what camera a node named and was not used, and why; empty when none
};

// Throws ParseError naming file and the JSON path of a transform or camera
// value that is not a finite number of its range (yfov in (0, pi),
// aspectRatio > 0), or of a camera whose view has no direction.
GltfCamera gltf_camera(const nlohmann::json& document, std::string_view file);

}  // namespace quiver
