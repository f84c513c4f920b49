// Editing a glTF's JSON text in tests: a document with other nodes.
#pragma once

#include <string>

namespace quiver::testing {

// `json` (a glTF with "scene": 0 before its "meshes") with its scenes and
// nodes replaced: one scene of `scene_nodes` and the array `nodes` (JSON).
inline std::string gltf_with_nodes(const std::string& json, const std::string& nodes, const std::string& scene_nodes) {
  const std::size_t from = json.find("\"scene\": 0");
  const std::size_t to = json.find("\"meshes\"");
  return json.substr(0, from) + "\"scene\": 0, \"scenes\": [{\"nodes\": " + scene_nodes + "}], \"nodes\": " + nodes +
         ",\n " + json.substr(to);
}

}  // namespace quiver::testing
