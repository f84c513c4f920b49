#include "io/reader_warnings.h"

#include "io/parse_error.h"

namespace quiver {

void ReaderWarnings::warn(std::string_view key, const FilePosition& at, std::string_view expected,
                          std::string_view found, std::string_view instead) {
  if (strict_) throw ParseError(at.file, at.line, at.column, expected, found);
  if (!key.empty()) {
    const auto seen = by_key_.find(key);
    if (seen != by_key_.end()) {
      ++findings_[seen->second].repeats;
      return;
    }
    by_key_.emplace(std::string(key), findings_.size());
  }
  findings_.push_back({joined({at.file, ":", std::to_string(at.line), ":", std::to_string(at.column),
                               ": warning: expected ", expected, ", found ", found, "; ", instead}),
                       0});
}

std::vector<std::string> ReaderWarnings::lines() const {
  std::vector<std::string> lines;
  for (const Finding& f : findings_) {
    lines.push_back(f.repeats == 0 ? f.text : joined({f.text, " (", std::to_string(f.repeats), " more like it)"}));
  }
  return lines;
}

}  // namespace quiver
