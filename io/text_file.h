// Reads a whole file into memory with a size bound checked while reading
// (no allocation beyond the bound). Problems with the file as a whole throw
// ParseError::whole_file naming the file and `what` it was meant to be.
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string_view>

namespace quiver {

// A file's bytes, as read_text_file read them.
class FileBytes {
 public:
  FileBytes() = default;
  FileBytes(std::unique_ptr<char[]> data, std::size_t size) : data_(std::move(data)), size_(size) {}

  const char* data() const { return data_.get(); }
  std::size_t size() const { return size_; }
  std::string_view view() const { return {data_.get(), size_}; }
  operator std::string_view() const { return view(); }

 private:
  std::unique_ptr<char[]> data_;
  std::size_t size_ = 0;
};

// Bytes per block of a file read on several threads: each thread reads its
// blocks straight into memory nobody has touched, so the page faults of
// a large file are shared out too.
inline constexpr std::size_t kFileReadBlockBytes = std::size_t{8} << 20;

// The bytes of `path`. Throws ParseError ("file: message") when it is
// missing, a directory or not a regular file (a FIFO, socket or device,
// which could block or never end), cannot be opened or read, or holds more
// than max_bytes; `what` names the file's role in messages ("an OBJ mesh",
// "a TOML scene"), and `bound_reason`, when given, follows the size bound
// in its message. The file is read in blocks of kFileReadBlockBytes on
// every thread into a buffer of its size; one whose size changes while
// read is read again, front to back, its bound checked as it grows.
FileBytes read_text_file(const std::filesystem::path& path, std::size_t max_bytes, std::string_view what,
                         std::string_view bound_reason = {});

}  // namespace quiver
