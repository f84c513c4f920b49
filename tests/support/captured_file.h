// Everything a test's code writes to a FILE*: a temporary file read back
// whole (the progress bar's and the status line's tests).
#pragma once

#include <cstdio>
#include <string>

namespace quiver::testing {

class CapturedFile {
 public:
  CapturedFile() : file_(std::tmpfile()) {}
  ~CapturedFile() {
    if (file_) std::fclose(file_);
  }
  CapturedFile(const CapturedFile&) = delete;
  CapturedFile& operator=(const CapturedFile&) = delete;

  std::FILE* file() const { return file_; }
  std::string text() const {
    std::fflush(file_);
    std::rewind(file_);
    std::string out;
    for (int c = std::fgetc(file_); c != EOF; c = std::fgetc(file_)) out.push_back(char(c));
    return out;
  }

 private:
  std::FILE* file_;
};

}  // namespace quiver::testing
