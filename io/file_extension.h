// File names compared without regard to ASCII case (".PNG" is ".png"),
// whatever the locale.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace quiver {

inline std::string ascii_lowercase(std::string_view text) {
  std::string lower(text);
  for (char& c : lower) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return lower;
}

// path's extension with its dot, in lower case ("" when it has none).
inline std::string lowercase_extension(const std::filesystem::path& path) {
  return ascii_lowercase(path.extension().string());
}

}  // namespace quiver
