#include "io/output_file.h"

#include <unistd.h>

#include <atomic>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>

namespace quiver {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail(const fs::path& path, const std::string& message) {
  throw std::runtime_error(path.string() + ": " + message);
}

// ".<name>.<kind>-<pid>-<n><extension>" beside target.
fs::path sibling_path(const fs::path& target, const char* kind) {
  static std::atomic<unsigned long> counter{0};
  std::string name = ".";
  name += target.filename().string();
  name += std::string(".") + kind + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter.fetch_add(1));
  name += target.extension().string();
  return target.parent_path() / name;
}

void remove_quietly(const fs::path& path) noexcept {
  std::error_code ignored;
  fs::remove(path, ignored);
}

// A committed target: whether it existed, and its earlier file kept as a hard link.
struct Replaced {
  fs::path target;
  bool existed = false;
  std::optional<fs::path> earlier;
};

// Puts back what the targets held before the commit began.
void restore(const std::vector<Replaced>& replaced) noexcept {
  for (auto it = replaced.rbegin(); it != replaced.rend(); ++it) {
    std::error_code ignored;
    if (it->earlier) {
      fs::rename(*it->earlier, it->target, ignored);
    } else if (!it->existed) {
      fs::remove(it->target, ignored);
    }  // else: a file system without hard links; the new file stays
  }
}

}  // namespace

void check_output_directory(const fs::path& path) {
  const fs::path parent = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  std::error_code error;
  const fs::file_status parent_status = fs::status(parent, error);
  if (!fs::exists(parent_status)) fail(path, "the directory '" + parent.string() + "' does not exist");
  if (!fs::is_directory(parent_status)) fail(path, "'" + parent.string() + "' is not a directory");
  if (fs::is_directory(fs::status(path, error))) fail(path, "is a directory");
}

StagedOutputs::~StagedOutputs() { discard(); }

void StagedOutputs::stage(const fs::path& target, const Writer& write) {
  const fs::path temporary = sibling_path(target, "tmp");
  staged_.reserve(staged_.size() + 1);  // the push below cannot throw once the file exists
  try {
    write(temporary);
  } catch (...) {
    remove_quietly(temporary);
    throw;
  }
  staged_.push_back({target, temporary});
}

void StagedOutputs::stage_bytes(const fs::path& target, std::string_view bytes) {
  stage(target, [&](const fs::path& temporary) {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) fail(target, "cannot create '" + temporary.string() + "'");
    out.write(bytes.data(), std::streamsize(bytes.size()));
    out.close();
    if (!out) fail(target, "cannot write '" + temporary.string() + "'");
  });
}

void StagedOutputs::commit() {
  // A device, FIFO or socket would be replaced by the rename: refuse before any target changes.
  for (const Staged& s : staged_) {
    std::error_code error;
    const fs::file_status status = fs::symlink_status(s.target, error);
    if (fs::exists(status) && !fs::is_regular_file(status) && !fs::is_symlink(status)) {
      discard();
      fail(s.target, "not a regular file; outputs are renamed into place and would replace it");
    }
  }
  std::vector<Replaced> replaced;
  replaced.reserve(staged_.size());
  for (std::size_t i = 0; i < staged_.size(); ++i) {
    const Staged s = staged_[i];
    std::error_code error;
    const fs::file_status status = fs::symlink_status(s.target, error);
    Replaced entry{s.target, fs::exists(status), std::nullopt};
    if (fs::is_regular_file(status)) {
      const fs::path earlier = sibling_path(s.target, "old");
      fs::create_hard_link(s.target, earlier, error);
      if (!error) entry.earlier = earlier;  // without hard links, the old file cannot be put back
    }
    fs::rename(s.temporary, s.target, error);
    if (error) {
      if (entry.earlier) remove_quietly(*entry.earlier);
      restore(replaced);
      staged_.erase(staged_.begin(), staged_.begin() + std::ptrdiff_t(i));
      discard();
      fail(s.target, "cannot replace the file: " + error.message());
    }
    replaced.push_back(std::move(entry));
  }
  for (const Replaced& r : replaced) {
    if (r.earlier) remove_quietly(*r.earlier);
  }
  staged_.clear();
}

void StagedOutputs::discard() noexcept {
  for (const Staged& s : staged_) remove_quietly(s.temporary);
  staged_.clear();
}

}  // namespace quiver
