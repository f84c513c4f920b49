#include "io/reader_warnings.h"

#include "io/parse_error.h"

namespace quiver {

void ReaderWarnings::warn(std::string_view key, const FilePosition& at, std::string_view expected,
                          std::string_view found, std::string_view instead) {
  // A finding about the file as a whole (line 0) names the file alone.
  const bool whole_file = at.line == 0;
  if (strict_ && whole_file) throw ParseError::whole_file(at.file, joined({"expected ", expected, ", found ", found}));
  if (strict_) throw ParseError(at.file, at.line, at.column, expected, found);
  if (!key.empty()) {
    const auto seen = by_key_.find(key);
    if (seen != by_key_.end()) {
      ++findings_[seen->second].repeats;
      return;
    }
    by_key_.emplace(std::string(key), findings_.size());
  }
  const std::string place =
      whole_file ? at.file : joined({at.file, ":", std::to_string(at.line), ":", std::to_string(at.column)});
  findings_.push_back({joined({place, ": warning: expected ", expected, ", found ", found, "; ", instead}), 0});
}

std::vector<std::string> ReaderWarnings::lines() const {
  std::vector<std::string> lines;
  for (const Finding& f : findings_) {
    lines.push_back(f.repeats == 0 ? f.text : joined({f.text, " (", std::to_string(f.repeats), " more like it)"}));
  }
  return lines;
}

}  // namespace quiver
