// The files a render writes, checked against each other and against the
// files it reads, so that no output ever replaces an input or another
// output. Two paths name the same file when they resolve to the same path
// (symlinks, "." and "..") or, both existing, share device and inode (hard
// links).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "scene/scene_desc.h"

namespace quiver {

// A file and its role in messages ("--stats", "the scene file", ...).
struct RoleFile {
  std::string role;
  std::filesystem::path path;
};

bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

// The files read for desc: desc.source_files (the first is "the scene
// file" when first_is_scene), then each texture image's file.
std::vector<RoleFile> files_read(const SceneDesc& desc, bool first_is_scene);

// Throws UsageError when two outputs name the same file, or an output names
// an input: "<output role> names '<path>', <input role> the render reads;
// choose another file".
void check_outputs_spare_inputs(const std::vector<RoleFile>& outputs, const std::vector<RoleFile>& inputs);

}  // namespace quiver
