// What a quiver.Scene holds: the scene description as read (from a file or
// from arrays) and the scene built from it once, for intersect and occluded
// (default build options, as `quiver trace` builds; a scene without a
// camera gets the default view first, which the queries do not use).
// Renders and camera rays start again from the description, so each gets
// the view and build options its own arguments ask for.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "io/mesh_append.h"
#include "scene/scene.h"
#include "scene/scene_desc.h"

namespace quiver {

struct PythonScene {
  std::string name;  // the file as given, or "<arrays>"; error messages start with it
  SceneDesc desc;
  Scene built;
  // Per hit id of built: the primitive's kind and index in its kind's input
  // list (Scene::origin), looked up once here rather than per hit.
  std::vector<std::int32_t> kind_of_id, index_of_id;
  // A scene from a dict (python/scene_dict.h): its TOML text, and the folder
  // its relative file names are resolved in.
  std::string toml_text;
  std::filesystem::path base_dir;
  MeshBytes held_meshes;  // its meshes given as arrays, by the file names the text gives them
};

// Builds the scene for queries; throws as build_named_scene (app/scene_build.h).
PythonScene make_python_scene(std::string name, SceneDesc desc);

}  // namespace quiver
