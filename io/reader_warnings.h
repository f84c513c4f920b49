// What a forgiving reader lets pass (a missing material library or texture,
// an undefined material, a trailing comment): one line per finding for the
// user, "file:line:column: warning: expected X, found Y; what happens
// instead" ("file: warning: ..." for the file as a whole, line 0); in
// strict mode the same finding is the ParseError it would otherwise have
// been. Each finding is reported once by its key (a file
// name, a material name), the repeats counted.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "scene/scene_desc.h"

namespace quiver {

class ReaderWarnings {
 public:
  explicit ReaderWarnings(bool strict) : strict_(strict) {}

  bool strict() const { return strict_; }

  // Strict: throws ParseError(at, expected, found). Otherwise records the
  // warning the first time `key` is seen (an empty key: every time) and
  // counts the repeats.
  void warn(std::string_view key, const FilePosition& at, std::string_view expected, std::string_view found,
            std::string_view instead);

  // The warnings in the order first seen, each with "(N more like it)" when repeated.
  std::vector<std::string> lines() const;

 private:
  struct Finding {
    std::string text;
    std::size_t repeats = 0;
  };
  bool strict_;
  std::vector<Finding> findings_;
  std::map<std::string, std::size_t, std::less<>> by_key_;
};

}  // namespace quiver
