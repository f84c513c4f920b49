// The error every scene reader throws for bad user input. what() reads
// "file:line:column: expected X, found Y": line and column are 1-based, the
// column counts bytes and points at the offending token, and Y is the token
// in single quotes (escaped and shortened) or "end of line" / "end of file".
// Problems with the file as a whole (cannot open it, too large) read
// "file: message" and have line() == column() == 0; when the file is one a
// scene names (a mesh, library or image), the error is moved to where it
// is named: "file:line:column: in the ROLE named here: file: message".
#pragma once

#include <cstddef>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <string_view>

#include "scene/scene_desc.h"

namespace quiver {

class ParseError : public std::runtime_error {
 public:
  ParseError(std::string_view file, std::size_t line, std::size_t column, std::string_view expected,
             std::string_view found);
  static ParseError whole_file(std::string_view file, std::string_view message);
  // cause (an error in a file the scene text names at `at`), reported
  // there when it concerns the file as a whole; role says what the file is
  // ("OBJ mesh"). A cause with its own line is returned as it is.
  static ParseError in_named_file(const FilePosition& at, std::string_view role, const ParseError& cause);

  const std::string& file() const { return file_; }
  std::size_t line() const { return line_; }
  std::size_t column() const { return column_; }

 private:
  ParseError(std::string_view file, std::size_t line, std::size_t column, std::string what);

  std::string file_;
  std::size_t line_ = 0;
  std::size_t column_ = 0;
};

// What an error says it found in a scene file that ends before any object.
inline constexpr std::string_view kNoObjectsFound = "end of file with no objects";

// A 1-based line and byte column.
struct TextPosition {
  std::size_t line, column;
};

// The position of byte `offset` of text whose lines end at '\n' (an offset
// past the end is the end).
TextPosition position_at(std::string_view text, std::size_t offset);
// The position just past the last byte: where an error found at the end of
// a file points.
inline TextPosition end_of_text(std::string_view text) { return position_at(text, text.size()); }

// The parts of a message, concatenated.
std::string joined(std::initializer_list<std::string_view> parts);

// A token as error messages show it: in single quotes, bytes outside
// printable ASCII written as \xNN, cut after 40 bytes with "...".
std::string quoted_token(std::string_view token);

}  // namespace quiver
