// The files a render writes, checked against each other and against the
// files it reads, so that no output ever replaces an input or another
// output. Two paths name the same file when they resolve to the same path
// (relative or absolute, symlinks, "." and ".."; the file need not exist)
// or, both existing, share device and inode (hard links).
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

// Whether a and b name one file: the same device and inode when both exist,
// else the same path once made absolute with the symlinks of its existing
// part resolved, or the same name in one folder reached two ways.
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

// Throws UsageError when an output names an existing file that is not a
// regular file (a device such as /dev/null, a FIFO, a socket, a directory):
// outputs are renamed into place, which would replace it.
void check_outputs_are_regular_files(const std::vector<RoleFile>& outputs);

// The files read for desc: desc.source_files (the first is "the scene
// file" when first_is_scene), then each texture image's file.
std::vector<RoleFile> files_read(const SceneDesc& desc, bool first_is_scene);

// Throws UsageError when two outputs name the same file, or an output names
// an input: "<output role> names '<path>', <input role> the render reads;
// choose another file".
void check_outputs_spare_inputs(const std::vector<RoleFile>& outputs, const std::vector<RoleFile>& inputs);

}  // namespace quiver
