// Which files a scene may name. A file named inside a scene (an OBJ's
// mtllib and map_Kd, a TOML scene's meshes and images, a glTF's buffers and
// images) must lie in the folder of the scene file quiver was asked to
// read, or below it, once "..", absolute paths and symlinks are resolved:
// a scene from elsewhere cannot make quiver read ../private or /etc. The
// rule is checked before the named file is opened or even looked at;
// `allow_outside` (--allow-outside-paths) lifts it.
#pragma once

#include <filesystem>
#include <string>

namespace quiver {

// The file `path` names, spelled one way: absolute, "." and ".." folded, and
// every symlink of its existing part resolved (the file need not exist).
std::filesystem::path resolved_path(const std::filesystem::path& path);

struct PathRule {
  bool allow_outside = false;
  // The folder named files must lie in; empty: the folder of the file that names them.
  std::filesystem::path root;

  // The rule for the files named by a file in `folder`: root set to folder when empty.
  PathRule for_folder(const std::filesystem::path& folder) const;
  // Whether `path` (as named, after joining it to its folder) may be read.
  bool admits(const std::filesystem::path& path) const;
  // What an error expected instead: "a file inside the scene's folder
  // '<root>' (--allow-outside-paths reads files elsewhere)".
  std::string expected() const;
};

}  // namespace quiver
