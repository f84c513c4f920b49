// Decoding base64 (the standard alphabet, '=' padding) for tests that move
// a glTF's data URI into a file.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace quiver::testing {

// The bytes a base64 text encodes.
inline std::string base64_decoded(std::string_view text) {
  constexpr std::string_view kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string bytes;
  std::uint32_t bits = 0;
  int count = 0;
  for (char c : text) {
    if (c == '=') break;
    bits = (bits << 6) | static_cast<std::uint32_t>(kAlphabet.find(c));
    if ((count += 6) >= 8) bytes += static_cast<char>((bits >> (count -= 8)) & 0xff);
  }
  return bytes;
}

}  // namespace quiver::testing
