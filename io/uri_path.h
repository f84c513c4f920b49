// glTF names its buffer and image files by URI (RFC 3986), so a space is
// written %20; Assimp 5.2 opens the text as written. Both quiver's checks
// and the Assimp module look for the file as written first, then
// percent-decoded.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "io/path_rule.h"

namespace quiver {

// `uri` with every %XY (two hexadecimal digits) replaced by that byte; a
// '%' not followed by two hexadecimal digits stays as it is.
inline std::string percent_decoded(std::string_view uri) {
  const auto hex = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  };
  std::string decoded;
  decoded.reserve(uri.size());
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && hex(uri[i + 1]) >= 0 && hex(uri[i + 2]) >= 0) {
      decoded += static_cast<char>(hex(uri[i + 1]) * 16 + hex(uri[i + 2]));
      i += 2;
    } else {
      decoded += uri[i];
    }
  }
  return decoded;
}

// The file a glTF URI names relative to `directory`: as written when that is
// a regular file, else percent-decoded (which may not exist either).
inline std::filesystem::path file_named_by_uri(const std::filesystem::path& directory, std::string_view uri) {
  const std::filesystem::path as_written = (directory / std::filesystem::path(uri)).lexically_normal();
  std::error_code error;
  if (std::filesystem::is_regular_file(as_written, error)) return as_written;
  return (directory / std::filesystem::path(percent_decoded(uri))).lexically_normal();
}

// Whether `paths` admits the file a URI names, both as written and
// percent-decoded (Assimp and quiver may open either).
inline bool uri_admitted(const PathRule& paths, const std::filesystem::path& directory, std::string_view uri) {
  return paths.admits(directory / std::filesystem::path(uri)) &&
         paths.admits(directory / std::filesystem::path(percent_decoded(uri)));
}

}  // namespace quiver
