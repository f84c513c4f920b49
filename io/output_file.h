// Output files that are never left half-written: checks made before a long
// render, and writing through a temporary file beside the target that is
// renamed over it only after it was written and closed.
#pragma once

#include <filesystem>
#include <functional>

namespace quiver {

// Throws std::runtime_error("<path>: <message>") when the parent directory
// is missing or not a directory, or the target is a directory.
void check_output_directory(const std::filesystem::path& path);

// Calls write(temporary) for a temporary name beside path (unique in and
// among processes, keeping path's extension), then renames it over path.
// If write throws or the rename fails, the temporary is removed, an
// existing target is untouched, and the error propagates (the rename
// failure as std::runtime_error("<path>: cannot replace the file: ...")).
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(const std::filesystem::path& temporary)>& write);

}  // namespace quiver
