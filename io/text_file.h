// Reads a whole text file into memory with a size bound checked while
// reading (no allocation beyond the bound). Problems with the file as a whole
// throw ParseError::whole_file naming the file and `what` it was meant to be.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

namespace quiver {

// The bytes of `path`. Throws ParseError ("file: message") when it is
// missing, a directory or not a regular file (a FIFO, socket or device,
// which could block or never end), cannot be opened or read, or holds more
// than max_bytes; `what` names the file's role in messages ("an OBJ mesh",
// "a TOML scene"), and `bound_reason`, when given, follows the size bound
// in its message. The string is sized once from the file's size.
std::string read_text_file(const std::filesystem::path& path, std::size_t max_bytes, std::string_view what,
                           std::string_view bound_reason = {});

}  // namespace quiver
