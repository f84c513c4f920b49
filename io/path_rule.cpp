#include "io/path_rule.h"

#include <algorithm>
#include <system_error>

namespace quiver {

namespace fs = std::filesystem;

fs::path resolved_path(const fs::path& path) {
  std::error_code error;
  const fs::path absolute = fs::absolute(path.empty() ? fs::path(".") : path, error);
  if (error) return path.lexically_normal();
  const fs::path result = fs::weakly_canonical(absolute, error);
  return error ? absolute.lexically_normal() : result;
}

PathRule PathRule::for_folder(const fs::path& folder) const {
  PathRule rule = *this;
  if (rule.root.empty()) rule.root = folder.empty() ? fs::path(".") : folder;
  return rule;
}

bool PathRule::admits(const fs::path& path) const {
  if (allow_outside) return true;
  const fs::path folder = resolved_path(root), file = resolved_path(path);
  // Inside when the folder's components are a proper prefix of the file's.
  const auto folder_end = folder.end(), file_end = file.end();
  const auto [in_folder, in_file] = std::mismatch(folder.begin(), folder_end, file.begin(), file_end);
  return (in_folder == folder_end || (std::next(in_folder) == folder_end && in_folder->empty())) &&
         in_file != file_end;
}

std::string PathRule::expected() const {
  return "a file inside the scene's folder '" + resolved_path(root).string() +
         "' (--allow-outside-paths reads files elsewhere)";
}

}  // namespace quiver
