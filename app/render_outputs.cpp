#include "app/render_outputs.h"

#include <system_error>

#include "app/render_options.h"
#include "io/file_extension.h"
#include "io/path_rule.h"

namespace quiver {

namespace fs = std::filesystem;

namespace {

// What an existing file is, for messages: "a directory", "a FIFO", ...
const char* kind_of(fs::file_type type) {
  switch (type) {
    case fs::file_type::directory: return "a directory";
    case fs::file_type::character: return "a character device";
    case fs::file_type::block: return "a block device";
    case fs::file_type::fifo: return "a FIFO";
    case fs::file_type::socket: return "a socket";
    default: return "not a regular file";
  }
}

}  // namespace

bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code error;
  if (fs::equivalent(a, b, error)) return true;  // false, with an error, unless both exist
  const fs::path resolved_a = resolved_path(a), resolved_b = resolved_path(b);
  if (resolved_a == resolved_b) return true;
  // One folder reached two ways (a bind mount): the same name in it.
  return resolved_a.filename() == resolved_b.filename() &&
         fs::equivalent(resolved_a.parent_path(), resolved_b.parent_path(), error);
}

void check_outputs_are_regular_files(const std::vector<RoleFile>& outputs) {
  for (const RoleFile& output : outputs) {
    std::error_code error;
    const fs::file_status status = fs::status(output.path, error);
    if (!fs::exists(status) || fs::is_regular_file(status)) continue;
    throw UsageError(output.role + " names '" + output.path.string() + "', " + kind_of(status.type()) +
                     "; outputs are written whole and renamed into place, so each must name a regular file "
                     "(new or existing)");
  }
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
