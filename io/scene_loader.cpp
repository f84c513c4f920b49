#include "io/scene_loader.h"

#include <string>

#include "io/nff_reader.h"
#include "io/obj_reader.h"
#include "io/parse_error.h"
#include "io/toml_reader.h"

namespace quiver {

SceneDesc load_scene(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  for (char& c : extension) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  if (extension == ".nff") return read_nff(path);
  if (extension == ".toml") return read_toml_scene(path);
  if (extension == ".obj") return read_obj_scene(path);
  const std::string shown = extension.empty() ? "no extension" : "extension '" + extension + "'";
  throw ParseError::whole_file(path.string(), "unknown scene format (" + shown + "): expected .nff, .toml or .obj");
}

}  // namespace quiver
