// quiver-mpi's checkpoint: the finished tiles of one render in a side file,
// so that `--resume` renders only the missing ones. The file is a header
// (the render's fingerprint, the image and tile sizes), written to a
// temporary and renamed over the path, then batches appended one per
// checkpoint interval, each with its length and a checksum and synced to
// disk before the next: a job killed at any moment leaves every batch
// before the one being written whole, and the reader stops at the first
// batch that is torn or fails its checksum.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include "app/render_outputs.h"
#include "integrator/render.h"
#include "scene/scene_desc.h"

namespace quiver {

// What a checkpoint must match to be resumed.
struct CheckpointKey {
  std::uint64_t fingerprint = 0;  // render_fingerprint
  std::uint32_t width = 0, height = 0, tile_size = 0, tiles = 0;
  bool operator==(const CheckpointKey&) const = default;
};

// A 64-bit hash of everything that decides the image's bits: the settings
// (size, anti-aliasing, depth, weight, seed, AOVs, tile size, sphere-test
// choice, two-sided surfaces), the crease angle, the final camera, the
// version and the bytes of every input file. Threads and SIMD width are
// left out: they change no bit. Throws std::runtime_error when an input
// cannot be read.
std::uint64_t render_fingerprint(const RenderSettings& settings, const SceneBuildOptions& build,
                                 const std::optional<double>& crease_angle, const CameraDesc& camera,
                                 const std::vector<RoleFile>& inputs, std::string_view version);

struct CheckpointTile {
  std::uint32_t tile = 0;
  std::vector<std::byte> bytes;  // FrameRenderer::pack_tile
};

struct CheckpointContents {
  std::vector<CheckpointTile> tiles;
  std::uint64_t valid_bytes = 0;  // the header and the whole batches
  std::size_t batches = 0;
};

// Reads the checkpoint at path. Throws std::runtime_error ("<path>: ...")
// when it cannot be read, is not a checkpoint, or was written for another
// render (key differs).
CheckpointContents read_checkpoint(const std::filesystem::path& path, const CheckpointKey& key);

class CheckpointWriter {
 public:
  // A new checkpoint holding no tile, replacing any file at path.
  static CheckpointWriter create(const std::filesystem::path& path, const CheckpointKey& key);
  // Appends to the checkpoint read_checkpoint read, cut to its valid bytes.
  static CheckpointWriter resume(const std::filesystem::path& path, const CheckpointContents& contents);

  CheckpointWriter(CheckpointWriter&& other) noexcept;
  CheckpointWriter& operator=(CheckpointWriter&&) = delete;
  ~CheckpointWriter();

  // One batch, synced to disk before it returns. Throws std::runtime_error.
  void append(std::span<const CheckpointTile> tiles);
  // Closes and deletes the file (the render is written).
  void remove();
  const std::filesystem::path& path() const { return path_; }

 private:
  CheckpointWriter(std::filesystem::path path, int fd) : path_(std::move(path)), fd_(fd) {}
  std::filesystem::path path_;
  int fd_ = -1;
};

}  // namespace quiver
