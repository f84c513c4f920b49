// Loads a scene file with the reader its extension names (.nff, .toml,
// .obj; .ply, .gltf, .glb and .stl through io/mesh_import.h;
// case-insensitive), and reads the image files its textures name.
#pragma once

#include <filesystem>
#include <optional>

#include "scene/scene_desc.h"

namespace quiver {

struct SceneLoadOptions {
  // The crease angle of every OBJ, PLY and STL mesh (the scene itself, or a TOML
  // [[meshes]] entry, over its `crease_angle` key), degrees in [0, 180];
  // 0 is faceted. Absent: a mesh's own key, else kDefaultCreaseAngleDegrees
  // (geometry/vertex_normals.h).
  std::optional<double> crease_angle_degrees;
  // Meshes (the scene, or TOML [[meshes]]) read strictly: what is
  // otherwise a warning in SceneDesc::warnings is an error (obj_reader.h).
  bool strict = false;
  // Files named inside the scene may lie outside its folder (io/path_rule.h).
  bool allow_outside_paths = false;
};

// Throws ParseError: from the reader or the texture images, or "file:
// message" for an extension that names no reader; std::invalid_argument
// for a crease angle outside [0, 180].
SceneDesc load_scene(const std::filesystem::path& path, const SceneLoadOptions& options = {});

}  // namespace quiver
