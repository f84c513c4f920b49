#include "app/checkpoint.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>

namespace quiver {

namespace {

namespace fs = std::filesystem;

constexpr char kMagic[8] = {'Q', 'V', 'R', 'C', 'K', 'P', 'T', '1'};
constexpr std::uint32_t kBatchMagic = 0x31425651;  // "QVB1"

// FNV-1a, 64 bits.
class Hash {
 public:
  void add(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) {
      value_ ^= p[i];
      value_ *= 0x100000001b3ull;
    }
  }
  template <class T>
  void add_value(const T& v) {
    add(&v, sizeof v);
  }
  void add_text(std::string_view text) {
    add_value(text.size());
    add(text.data(), text.size());
  }
  std::uint64_t value() const { return value_; }

 private:
  std::uint64_t value_ = 0xcbf29ce484222325ull;
};

[[noreturn]] void fail(const fs::path& path, const std::string& message) {
  throw std::runtime_error(path.string() + ": " + message);
}

std::string errno_text() { return std::strerror(errno); }

void put(std::vector<std::byte>& out, const void* data, std::size_t n) {
  const std::size_t at = out.size();
  out.resize(at + n);
  if (n > 0) std::memcpy(out.data() + at, data, n);
}
template <class T>
void put_value(std::vector<std::byte>& out, const T& v) {
  put(out, &v, sizeof v);
}

std::vector<std::byte> header_bytes(const CheckpointKey& key) {
  std::vector<std::byte> out;
  put(out, kMagic, sizeof kMagic);
  put_value(out, key.fingerprint);
  put_value(out, key.width);
  put_value(out, key.height);
  put_value(out, key.tile_size);
  put_value(out, key.tiles);
  Hash h;
  h.add(out.data(), out.size());
  put_value(out, h.value());
  return out;
}

void write_all(int fd, const fs::path& path, const std::vector<std::byte>& bytes) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail(path, "cannot write the checkpoint: " + errno_text());
    }
    done += std::size_t(n);
  }
}

void sync(int fd, const fs::path& path) {
  if (::fdatasync(fd) != 0) fail(path, "cannot sync the checkpoint: " + errno_text());
}

// A reader over the file's bytes that says when it ran out.
struct Cursor {
  const std::vector<std::byte>& bytes;
  std::size_t at = 0;
  bool take(void* out, std::size_t n) {
    if (bytes.size() - at < n) return false;
    std::memcpy(out, bytes.data() + at, n);
    at += n;
    return true;
  }
  template <class T>
  bool take_value(T& v) {
    return take(&v, sizeof v);
  }
};

}  // namespace

std::uint64_t render_fingerprint(const RenderSettings& settings, const SceneBuildOptions& build,
                                 const std::optional<double>& crease_angle, const CameraDesc& camera,
                                 const std::vector<RoleFile>& inputs, std::string_view version) {
  Hash h;
  h.add_text(version);
  h.add_value(settings.width);
  h.add_value(settings.height);
  h.add_text(to_string(settings.aa));
  h.add_value(settings.trace.max_depth);
  h.add_value(settings.trace.min_weight);
  h.add_value(settings.trace.seed);
  h.add_value(settings.trace.spawn_every_ray);
  h.add_value(settings.trace.filter_textures);
  h.add_value(settings.aov_depth);
  h.add_value(settings.aov_normal);
  h.add_value(settings.aov_id);
  h.add_value(settings.tile_size);
  h.add_value(settings.methods);
  h.add_value(build.all_two_sided);
  h.add_value(crease_angle.has_value());
  h.add_value(crease_angle.value_or(0.0));
  for (const Vec3<float>& v : {camera.from, camera.at, camera.up}) {
    h.add_value(v.x);
    h.add_value(v.y);
    h.add_value(v.z);
  }
  h.add_value(camera.angle_degrees);
  for (const RoleFile& input : inputs) {
    std::ifstream in(input.path, std::ios::binary);
    if (!in) fail(input.path, "cannot read it to fingerprint the render");
    std::vector<char> buffer(1 << 16);
    std::size_t size = 0;
    while (in) {
      in.read(buffer.data(), std::streamsize(buffer.size()));
      const std::size_t n = std::size_t(in.gcount());
      h.add(buffer.data(), n);
      size += n;
    }
    if (!in.eof()) fail(input.path, "cannot read it to fingerprint the render");
    h.add_value(size);
  }
  return h.value();
}

CheckpointContents read_checkpoint(const fs::path& path, const CheckpointKey& key) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open the checkpoint (nothing to resume)");
  std::vector<std::byte> bytes;
  {
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    if (size < 0) fail(path, "cannot read the checkpoint");
    in.seekg(0);
    bytes.resize(std::size_t(size));
    in.read(reinterpret_cast<char*>(bytes.data()), size);
    if (!in) fail(path, "cannot read the checkpoint");
  }
  const std::vector<std::byte> expected = header_bytes(key);
  if (bytes.size() < expected.size() || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0) {
    fail(path, "not a quiver-mpi checkpoint");
  }
  if (std::memcmp(bytes.data(), expected.data(), expected.size()) != 0) {
    fail(path, "the checkpoint was written for another render (scene, settings or version differ); remove it or "
               "render without --resume");
  }
  CheckpointContents contents;
  Cursor cursor{bytes, expected.size()};
  contents.valid_bytes = cursor.at;
  while (true) {
    const std::size_t start = cursor.at;
    std::uint32_t magic = 0, count = 0;
    if (!cursor.take_value(magic) || magic != kBatchMagic || !cursor.take_value(count)) break;
    std::vector<CheckpointTile> batch;
    bool whole = true;
    for (std::uint32_t i = 0; i < count && whole; ++i) {
      CheckpointTile tile;
      std::uint32_t n = 0;
      whole = cursor.take_value(tile.tile) && cursor.take_value(n) && tile.tile < key.tiles &&
              bytes.size() - cursor.at >= n;
      if (!whole) break;
      tile.bytes.resize(n);
      cursor.take(tile.bytes.data(), n);
      batch.push_back(std::move(tile));
    }
    Hash h;
    h.add(bytes.data() + start, cursor.at - start);
    std::uint64_t checksum = 0;
    if (!whole || !cursor.take_value(checksum) || checksum != h.value()) break;
    for (CheckpointTile& tile : batch) contents.tiles.push_back(std::move(tile));
    contents.valid_bytes = cursor.at;
    ++contents.batches;
  }
  return contents;
}

CheckpointWriter CheckpointWriter::create(const fs::path& path, const CheckpointKey& key) {
  fs::path temporary = path;
  temporary += ".tmp" + std::to_string(::getpid());
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail(path, "cannot create the checkpoint '" + temporary.string() + "': " + errno_text());
  try {
    write_all(fd, path, header_bytes(key));
    sync(fd, path);
    std::error_code error;
    fs::rename(temporary, path, error);
    if (error) fail(path, "cannot create the checkpoint: " + error.message());
  } catch (...) {
    ::close(fd);
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw;
  }
  return CheckpointWriter(path, fd);
}

CheckpointWriter CheckpointWriter::resume(const fs::path& path, const CheckpointContents& contents) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) fail(path, "cannot open the checkpoint: " + errno_text());
  if (::ftruncate(fd, off_t(contents.valid_bytes)) != 0 || ::lseek(fd, 0, SEEK_END) < 0) {
    const std::string message = errno_text();
    ::close(fd);
    fail(path, "cannot continue the checkpoint: " + message);
  }
  return CheckpointWriter(path, fd);
}

CheckpointWriter::CheckpointWriter(CheckpointWriter&& other) noexcept
    : path_(std::move(other.path_)), fd_(std::exchange(other.fd_, -1)) {}

CheckpointWriter::~CheckpointWriter() {
  if (fd_ >= 0) ::close(fd_);
}

void CheckpointWriter::append(std::span<const CheckpointTile> tiles) {
  if (tiles.empty()) return;
  std::vector<std::byte> out;
  put_value(out, kBatchMagic);
  put_value(out, std::uint32_t(tiles.size()));
  for (const CheckpointTile& tile : tiles) {
    put_value(out, tile.tile);
    put_value(out, std::uint32_t(tile.bytes.size()));
    put(out, tile.bytes.data(), tile.bytes.size());
  }
  Hash h;
  h.add(out.data(), out.size());
  put_value(out, h.value());
  write_all(fd_, path_, out);
  sync(fd_, path_);
}

void CheckpointWriter::remove() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  std::error_code ignored;
  fs::remove(path_, ignored);
}

}  // namespace quiver
