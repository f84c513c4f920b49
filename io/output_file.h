// Output files that are never left half-written and never lost: checks made
// before a long render, and writing through temporary files beside the
// targets that are renamed over them only after every one of them was
// written and closed.
#pragma once

#include <filesystem>
#include <functional>
#include <string_view>
#include <vector>

namespace quiver {

// Throws std::runtime_error("<path>: <message>") when the parent directory
// is missing or not a directory, or the target is a directory.
void check_output_directory(const std::filesystem::path& path);

// Outputs written together: stage() writes each to a temporary name beside
// its target (unique in and among processes, keeping the target's
// extension); commit() renames them over their targets in staging order.
// While committing, a target that existed is kept as a hard link, so when a
// rename fails the targets already replaced get their old files back and
// the ones that did not exist are removed (on a file system without hard
// links a replaced file cannot be put back). Temporaries not committed are
// removed by discard() and the destructor. Not copyable.
class StagedOutputs {
 public:
  using Writer = std::function<void(const std::filesystem::path& temporary)>;

  StagedOutputs() = default;
  StagedOutputs(const StagedOutputs&) = delete;
  StagedOutputs& operator=(const StagedOutputs&) = delete;
  ~StagedOutputs();

  // Calls write(temporary). If it throws, that temporary is removed and the
  // error propagates; what was staged before stays staged.
  void stage(const std::filesystem::path& target, const Writer& write);
  // stage() of a file holding `bytes`; std::runtime_error("<target>: cannot
  // create ..." or "cannot write ...") when that fails.
  void stage_bytes(const std::filesystem::path& target, std::string_view bytes);

  // Renames every staged temporary over its target. A target that exists
  // and is neither a regular file nor a symlink (a device, a FIFO, a
  // socket, a directory) fails the whole commit before any rename. On a failed rename the
  // targets are put back as described above, the remaining temporaries are
  // removed, and std::runtime_error("<path>: cannot replace the file: ...")
  // is thrown.
  void commit();

  // Removes the temporaries not committed.
  void discard() noexcept;

 private:
  struct Staged {
    std::filesystem::path target, temporary;
  };
  std::vector<Staged> staged_;
};

}  // namespace quiver
