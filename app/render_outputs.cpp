#include "app/render_outputs.h"

#include <system_error>

#include "app/render_options.h"
#include "io/file_extension.h"

namespace quiver {

namespace fs = std::filesystem;

bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code error;
  if (fs::equivalent(a, b, error)) return true;  // false, with an error, unless both exist
  const fs::path resolved_a = fs::weakly_canonical(a, error);
  if (error) return false;
  const fs::path resolved_b = fs::weakly_canonical(b, error);
  return !error && resolved_a == resolved_b;
}

std::vector<RoleFile> files_read(const SceneDesc& desc, bool first_is_scene) {
  std::vector<RoleFile> files;
  for (std::size_t i = 0; i < desc.source_files.size(); ++i) {
    const fs::path path = desc.source_files[i];
    const std::string extension = lowercase_extension(path);
    const char* role = i == 0 && first_is_scene ? "the scene file"
                       : extension == ".mtl"    ? "an MTL material library"
                       : extension == ".obj"    ? "an OBJ mesh"
                                                : "a mesh";
    files.push_back({role, path});
  }
  for (const TextureDesc& texture : desc.textures) {
    if (!texture.path.empty()) files.push_back({"a texture image", texture.path});
  }
  return files;
}

void check_outputs_spare_inputs(const std::vector<RoleFile>& outputs, const std::vector<RoleFile>& inputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (same_file(outputs[i].path, outputs[j].path)) {
        throw UsageError(outputs[j].role + " and " + outputs[i].role + " name the same file ('" +
                         outputs[i].path.string() + "')");
      }
    }
    for (const RoleFile& input : inputs) {
      if (same_file(outputs[i].path, input.path)) {
        throw UsageError(outputs[i].role + " names '" + outputs[i].path.string() + "', " + input.role +
                         " the render reads ('" + input.path.string() + "'); choose another file");
      }
    }
  }
}

}  // namespace quiver
