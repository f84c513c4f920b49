// How a quiver module (io/module_loader.h) hands a message back across its
// C-style boundary: on one line (line breaks become "; "), cut to fit the
// caller's buffer, NUL-terminated.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <string>
#include <string_view>

namespace quiver {

inline void copy_message(std::string_view message, char* error, std::size_t error_size) {
  if (error == nullptr || error_size == 0) return;
  while (!message.empty() && message.back() == '\n') message.remove_suffix(1);
  std::string line;
  for (char c : message) line += c == '\n' ? std::string_view("; ") : std::string_view(&c, 1);
  const std::size_t length = std::min(line.size(), error_size - 1);
  std::memcpy(error, line.data(), length);
  error[length] = '\0';
}

}  // namespace quiver
