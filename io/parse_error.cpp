#include "io/parse_error.h"

#include <algorithm>

namespace quiver {

namespace {

std::string position_message(std::string_view file, std::size_t line, std::size_t column,
                             std::string_view expected, std::string_view found) {
  std::string message(file);
  message += ':';
  message += std::to_string(line);
  message += ':';
  message += std::to_string(column);
  message += ": expected ";
  message += expected;
  message += ", found ";
  message += found;
  return message;
}

}  // namespace

ParseError::ParseError(std::string_view file, std::size_t line, std::size_t column,
                       std::string_view expected, std::string_view found)
    : std::runtime_error(position_message(file, line, column, expected, found)),
      file_(file),
      line_(line),
      column_(column) {}

ParseError::ParseError(std::string_view file, std::size_t line, std::size_t column, std::string what)
    : std::runtime_error(std::move(what)), file_(file), line_(line), column_(column) {}

ParseError ParseError::whole_file(std::string_view file, std::string_view message) {
  return ParseError(file, 0, 0, joined({file, ": ", message}));
}

ParseError ParseError::in_named_file(const FilePosition& at, std::string_view role, const ParseError& cause) {
  if (cause.line() != 0) return cause;  // already at its place in the named file
  return ParseError(at.file, at.line, at.column,
                    joined({at.file, ":", std::to_string(at.line), ":", std::to_string(at.column), ": in the ", role,
                            " named here: ", cause.what()}));
}

std::string quoted_token(std::string_view token) {
  constexpr std::size_t kShownBytes = 40;
  constexpr char kHex[] = "0123456789ABCDEF";
  std::string quoted = "'";
  for (std::size_t i = 0; i < token.size() && i < kShownBytes; ++i) {
    const auto byte = static_cast<unsigned char>(token[i]);
    if (byte >= 0x20 && byte < 0x7f) {
      quoted += static_cast<char>(byte);
    } else {
      quoted += "\\x";
      quoted += kHex[byte >> 4];
      quoted += kHex[byte & 0xf];
    }
  }
  if (token.size() > kShownBytes) quoted += "...";
  quoted += '\'';
  return quoted;
}

TextPosition position_at(std::string_view text, std::size_t offset) {
  const std::string_view before = text.substr(0, std::min(offset, text.size()));
  const std::size_t last_newline = before.rfind('\n');
  const std::size_t line_start = last_newline == std::string_view::npos ? 0 : last_newline + 1;
  const auto lines = static_cast<std::size_t>(std::count(before.begin(), before.end(), '\n'));
  return {lines + 1, before.size() - line_start + 1};
}

std::string joined(std::initializer_list<std::string_view> parts) {
  std::string text;
  for (std::string_view part : parts) text += part;
  return text;
}

}  // namespace quiver
