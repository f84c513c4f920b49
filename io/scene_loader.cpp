#include "io/scene_loader.h"

#include <string>

#include "geometry/vertex_normals.h"
#include "io/file_extension.h"
#include "io/mesh_import.h"
#include "io/nff_reader.h"
#include "io/obj_reader.h"
#include "io/parse_error.h"
#include "io/path_rule.h"
#include "io/texture_image.h"
#include "io/toml_reader.h"

namespace quiver {

SceneDesc load_scene(const std::filesystem::path& path, const SceneLoadOptions& options) {
  const std::string extension = lowercase_extension(path);
  const PathRule paths = PathRule{options.allow_outside_paths, {}}.for_folder(path.parent_path());
  const double crease_angle = options.crease_angle_degrees.value_or(kDefaultCreaseAngleDegrees);
  SceneDesc scene;
  if (extension == ".nff") {
    scene = read_nff(path);
  } else if (extension == ".toml") {
    scene = read_toml_scene(path, options.crease_angle_degrees, options.strict, paths);
  } else if (extension == ".obj") {
    scene = read_obj_scene(path, crease_angle, options.strict, kMaxObjTriangles, paths);
  } else if (is_imported_mesh_extension(extension)) {
    scene = read_imported_mesh(path, crease_angle, options.strict, kMaxObjTriangles, paths);
  } else {
    const std::string shown = extension.empty() ? "no extension" : "extension '" + extension + "'";
    throw ParseError::whole_file(
        path.string(), "unknown scene format (" + shown + "): expected .nff, .toml, .obj, .ply, .gltf, .glb or .stl");
  }
  scene.source_files.insert(scene.source_files.begin(), path.string());
  read_texture_images(scene);
  return scene;
}

}  // namespace quiver
