#include "io/text_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <string>
#include <system_error>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "io/parse_error.h"

namespace quiver {

namespace {

// Closes a file descriptor, if one was opened, when it goes.
struct OpenFile {
  int fd;
  ~OpenFile() {
    if (fd >= 0) ::close(fd);
  }
};

// Reads up to `count` bytes at `offset` into `out`, retrying short reads;
// the bytes read (fewer at the end of the file), or -1 on an error.
std::int64_t read_at(int fd, char* out, std::size_t count, std::size_t offset) {
  std::size_t done = 0;
  while (done < count) {
    const ssize_t got = ::pread(fd, out + done, count - done, static_cast<off_t>(offset + done));
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) return -1;
    if (got == 0) break;
    done += static_cast<std::size_t>(got);
  }
  return static_cast<std::int64_t>(done);
}

}  // namespace

FileBytes read_text_file(const std::filesystem::path& path, std::size_t max_bytes, std::string_view what,
                         std::string_view bound_reason) {
  const std::string name = path.string();
  auto fail = [&](std::string_view problem) {
    std::string message = "cannot read ";
    message += what;
    message += ": ";
    message += problem;
    throw ParseError::whole_file(name, message);
  };
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (!std::filesystem::exists(status)) fail("no such file");
  if (std::filesystem::is_directory(status)) fail("it is a directory");
  // A FIFO, socket or device could block or never end.
  if (!std::filesystem::is_regular_file(status)) fail("not a regular file");
  const OpenFile file{::open(path.c_str(), O_RDONLY | O_CLOEXEC)};
  if (file.fd < 0) fail("cannot open it");
  auto too_large = [&] {
    std::string message = "larger than the limit of " + std::to_string(max_bytes) + " bytes";
    if (!bound_reason.empty()) message += " (" + std::string(bound_reason) + ")";
    fail(message);
  };
  struct stat stated {};
  if (::fstat(file.fd, &stated) != 0) fail("read error");
  const auto size = static_cast<std::size_t>(stated.st_size);
  if (size > max_bytes) too_large();
  // One byte more than the size: reading it tells whether the file grew.
  std::unique_ptr<char[]> data(new char[size + 1]);
  std::atomic<bool> short_read{false}, failed{false};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, size, kFileReadBlockBytes),
                    [&](const tbb::blocked_range<std::size_t>& block) {
                      const std::int64_t got = read_at(file.fd, data.get() + block.begin(), block.size(), block.begin());
                      if (got < 0) failed = true;
                      if (got >= 0 && std::size_t(got) < block.size()) short_read = true;
                    });
  if (failed) fail("read error");
  const std::int64_t beyond = read_at(file.fd, data.get() + size, 1, size);
  if (beyond < 0) fail("read error");
  if (!short_read && beyond == 0) return FileBytes(std::move(data), size);
  // The size changed while read (or was never true, as procfs states 0):
  // front to back in blocks, the bound checked as the text grows.
  std::vector<char> text;
  std::vector<char> block(std::size_t{1} << 16);
  for (;;) {
    const std::int64_t got = read_at(file.fd, block.data(), block.size(), text.size());
    if (got < 0) fail("read error");
    if (got == 0) break;
    if (std::size_t(got) > max_bytes - text.size()) too_large();
    text.insert(text.end(), block.begin(), block.begin() + got);
  }
  std::unique_ptr<char[]> copy(new char[text.size() + 1]);
  std::memcpy(copy.get(), text.data(), text.size());
  return FileBytes(std::move(copy), text.size());
}

}  // namespace quiver
