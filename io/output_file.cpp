#include "io/output_file.h"

#include <unistd.h>

#include <atomic>
#include <stdexcept>
#include <string>
#include <system_error>

namespace quiver {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail(const fs::path& path, const std::string& message) {
  throw std::runtime_error(path.string() + ": " + message);
}

fs::path temporary_path(const fs::path& target) {
  static std::atomic<unsigned long> counter{0};
  std::string name = ".";
  name += target.filename().string();
  name += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter.fetch_add(1));
  name += target.extension().string();
  return target.parent_path() / name;
}

// Removes the file on scope exit unless committed.
class TemporaryFile {
 public:
  explicit TemporaryFile(fs::path path) : path_(std::move(path)) {}
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;
  ~TemporaryFile() {
    if (!committed_) {
      std::error_code ignored;
      fs::remove(path_, ignored);
    }
  }
  const fs::path& path() const { return path_; }
  void commit() { committed_ = true; }

 private:
  fs::path path_;
  bool committed_ = false;
};

}  // namespace

void check_output_directory(const fs::path& path) {
  const fs::path parent = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  std::error_code error;
  const fs::file_status parent_status = fs::status(parent, error);
  if (!fs::exists(parent_status)) fail(path, "the directory '" + parent.string() + "' does not exist");
  if (!fs::is_directory(parent_status)) fail(path, "'" + parent.string() + "' is not a directory");
  if (fs::is_directory(fs::status(path, error))) fail(path, "is a directory");
}

void write_file_atomically(const fs::path& path, const std::function<void(const fs::path& temporary)>& write) {
  TemporaryFile temporary(temporary_path(path));
  write(temporary.path());
  std::error_code error;
  fs::rename(temporary.path(), path, error);
  if (error) fail(path, "cannot replace the file: " + error.message());
  temporary.commit();
}

}  // namespace quiver
