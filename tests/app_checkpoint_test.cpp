// quiver-mpi's checkpoint (app/checkpoint.h): batches read back whole; a
// torn or corrupted last batch, or one naming a tile past the last, is
// dropped and the ones before it kept; a resumed file continues after its
// valid part; a checkpoint of another render is refused; the fingerprint
// follows the settings, the camera and the input files' bytes.
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "app/checkpoint.h"
#include "support/temporary_directory.h"

namespace quiver {
namespace {

namespace fs = std::filesystem;

CheckpointTile tile(std::uint32_t index, std::size_t bytes) {
  CheckpointTile t{index, std::vector<std::byte>(bytes)};
  for (std::size_t i = 0; i < bytes; ++i) t.bytes[i] = std::byte((index * 31 + i) & 0xff);
  return t;
}

const CheckpointKey kKey{0x1234, 64, 48, 16, 12};

TEST(Checkpoint, BatchesReadBackAndATornLastBatchIsDropped) {
  testing::TemporaryDirectory dir;
  const fs::path path = dir.path() / "render.checkpoint";
  {
    CheckpointWriter writer = CheckpointWriter::create(path, kKey);
    EXPECT_EQ(read_checkpoint(path, kKey).tiles.size(), 0u);
    const std::vector<CheckpointTile> first{tile(3, 100), tile(7, 40)}, second{tile(0, 8)};
    writer.append(first);
    writer.append(second);
  }
  const CheckpointContents whole = read_checkpoint(path, kKey);
  ASSERT_EQ(whole.tiles.size(), 3u);
  EXPECT_EQ(whole.batches, 2u);
  const CheckpointTile written[] = {tile(3, 100), tile(7, 40), tile(0, 8)};
  for (std::size_t k = 0; k < 3; ++k) {  // every tile, in order, index and bytes
    EXPECT_EQ(whole.tiles[k].tile, written[k].tile) << k;
    EXPECT_EQ(whole.tiles[k].bytes, written[k].bytes) << k;
  }
  EXPECT_EQ(whole.valid_bytes, fs::file_size(path));

  // Cut inside the second batch: only the first is kept.
  fs::resize_file(path, whole.valid_bytes - 5);
  const CheckpointContents torn = read_checkpoint(path, kKey);
  EXPECT_EQ(torn.tiles.size(), 2u);
  EXPECT_EQ(torn.batches, 1u);

  // Resumed: appended after the valid part, the torn bytes gone.
  {
    CheckpointWriter writer = CheckpointWriter::resume(path, torn);
    const std::vector<CheckpointTile> third{tile(11, 20)};
    writer.append(third);
  }
  const CheckpointContents resumed = read_checkpoint(path, kKey);
  ASSERT_EQ(resumed.tiles.size(), 3u);
  EXPECT_EQ(resumed.tiles[2].tile, 11u);
  EXPECT_EQ(resumed.tiles[2].bytes, tile(11, 20).bytes);
}

TEST(Checkpoint, ACorruptedBatchEndsWhatIsRead) {
  testing::TemporaryDirectory dir;
  const fs::path path = dir.path() / "c";
  std::uintmax_t after_first = 0;
  {
    CheckpointWriter writer = CheckpointWriter::create(path, kKey);
    const std::vector<CheckpointTile> first{tile(1, 16)}, second{tile(2, 16)};
    writer.append(first);
    after_first = fs::file_size(path);
    writer.append(second);
  }
  {
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(std::streamoff(after_first + 20));
    f.put('\x5a');
  }
  const CheckpointContents contents = read_checkpoint(path, kKey);
  ASSERT_EQ(contents.tiles.size(), 1u);
  EXPECT_EQ(contents.tiles[0].tile, 1u);
}

// A whole batch naming a tile past the image's last (a file from a buggy or
// hostile writer) ends what is read, like a corrupted one.
TEST(Checkpoint, ATileIndexPastTheLastEndsWhatIsRead) {
  testing::TemporaryDirectory dir;
  const fs::path path = dir.path() / "c";
  {
    CheckpointWriter writer = CheckpointWriter::create(path, kKey);
    const std::vector<CheckpointTile> last{tile(kKey.tiles - 1, 8)}, past{tile(kKey.tiles, 8)};
    writer.append(last);
    writer.append(past);
  }
  const CheckpointContents contents = read_checkpoint(path, kKey);
  ASSERT_EQ(contents.tiles.size(), 1u);
  EXPECT_EQ(contents.tiles[0].tile, kKey.tiles - 1);
  EXPECT_LT(contents.valid_bytes, fs::file_size(path));
}

TEST(Checkpoint, AnotherRendersCheckpointOrAnotherFileIsRefused) {
  testing::TemporaryDirectory dir;
  const fs::path path = dir.path() / "c";
  CheckpointWriter::create(path, kKey);
  CheckpointKey other = kKey;
  other.fingerprint ^= 1;
  EXPECT_THROW(read_checkpoint(path, other), std::runtime_error);
  other = kKey;
  other.width = 65;
  EXPECT_THROW(read_checkpoint(path, other), std::runtime_error);
  EXPECT_THROW(read_checkpoint(dir.path() / "missing", kKey), std::runtime_error);
  std::ofstream(dir.path() / "text") << "not a checkpoint at all, just text";
  EXPECT_THROW(read_checkpoint(dir.path() / "text", kKey), std::runtime_error);
}

TEST(Checkpoint, CreatingReplacesAnOldCheckpointAndRemoveDeletesIt) {
  testing::TemporaryDirectory dir;
  const fs::path path = dir.path() / "c";
  {
    CheckpointWriter writer = CheckpointWriter::create(path, kKey);
    const std::vector<CheckpointTile> first{tile(1, 16)};
    writer.append(first);
  }
  CheckpointWriter writer = CheckpointWriter::create(path, kKey);
  EXPECT_EQ(read_checkpoint(path, kKey).tiles.size(), 0u);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 1);  // no temporary left
  writer.remove();
  EXPECT_FALSE(fs::exists(path));
}

TEST(Checkpoint, TheFingerprintFollowsSettingsCameraAndInputBytes) {
  testing::TemporaryDirectory dir;
  const fs::path scene = dir.path() / "scene.nff";
  std::ofstream(scene) << "s 0 0 0 1\n";
  RenderSettings settings;
  const SceneBuildOptions build;
  CameraDesc camera{{0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 45.f, 1.f, 64, 64};
  const std::vector<RoleFile> inputs{{"the scene file", scene}};
  const std::uint64_t base = render_fingerprint(settings, build, std::nullopt, camera, inputs, "1");
  EXPECT_EQ(render_fingerprint(settings, build, std::nullopt, camera, inputs, "1"), base);
  RenderSettings threads = settings;
  threads.threads = 7;
  threads.isa = Isa::avx2;
  EXPECT_EQ(render_fingerprint(threads, build, std::nullopt, camera, inputs, "1"), base);
  RenderSettings seed = settings;
  seed.trace.seed = 1;
  EXPECT_NE(render_fingerprint(seed, build, std::nullopt, camera, inputs, "1"), base);
  RenderSettings aa = settings;
  aa.aa = parse_anti_aliasing("adaptive:0.1:3");
  EXPECT_NE(render_fingerprint(aa, build, std::nullopt, camera, inputs, "1"), base);
  RenderSettings point_sampled = settings;
  point_sampled.trace.filter_textures = false;
  EXPECT_NE(render_fingerprint(point_sampled, build, std::nullopt, camera, inputs, "1"), base);
  EXPECT_NE(render_fingerprint(settings, build, 30.0, camera, inputs, "1"), base);
  EXPECT_NE(render_fingerprint(settings, build, std::nullopt, camera, inputs, "2"), base);
  CameraDesc moved = camera;
  moved.from.x = 0.5f;
  EXPECT_NE(render_fingerprint(settings, build, std::nullopt, moved, inputs, "1"), base);
  std::ofstream(scene) << "s 0 0 0 2\n";
  EXPECT_NE(render_fingerprint(settings, build, std::nullopt, camera, inputs, "1"), base);
  fs::remove(scene);
  EXPECT_THROW(render_fingerprint(settings, build, std::nullopt, camera, inputs, "1"), std::runtime_error);
}

// Every setting that changes a pixel, and the camera's every coordinate,
// changes the fingerprint: a checkpoint of another render is never resumed.
TEST(Checkpoint, EverySettingThatChangesPixelsChangesTheFingerprint) {
  testing::TemporaryDirectory dir;
  const fs::path scene = dir.path() / "scene.nff";
  std::ofstream(scene) << "s 0 0 0 1\n";
  const std::vector<RoleFile> inputs{{"the scene file", scene}};
  const RenderSettings settings;
  const SceneBuildOptions build;
  const CameraDesc camera{{0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 45.f, 1.f, 64, 64};
  const std::uint64_t base = render_fingerprint(settings, build, std::nullopt, camera, inputs, "1");
  using Change = std::function<void(RenderSettings&, SceneBuildOptions&, CameraDesc&)>;
  const std::vector<std::pair<const char*, Change>> changes{
      {"width", [](RenderSettings& s, SceneBuildOptions&, CameraDesc&) { s.width += 1; }},
      {"height", [](RenderSettings& s, SceneBuildOptions&, CameraDesc&) { s.height += 1; }},
      {"max_depth", [](RenderSettings& s, SceneBuildOptions&, CameraDesc&) { s.trace.max_depth += 1; }},
      {"min_weight", [](RenderSettings& s, SceneBuildOptions&, CameraDesc&) { s.trace.min_weight *= 2.f; }},
      {"spawn_every_ray", [](RenderSettings& s, SceneBuildOptions&, CameraDesc&) { s.trace.spawn_every_ray ^= true; }},
      {"aov_depth", [](RenderSettings& s, SceneBuildOptions&, CameraDesc&) { s.aov_depth ^= true; }},
      {"aov_normal", [](RenderSettings& s, SceneBuildOptions&, CameraDesc&) { s.aov_normal ^= true; }},
      {"aov_id", [](RenderSettings& s, SceneBuildOptions&, CameraDesc&) { s.aov_id ^= true; }},
      {"tile_size", [](RenderSettings& s, SceneBuildOptions&, CameraDesc&) { s.tile_size *= 2; }},
      {"methods", [](RenderSettings& s, SceneBuildOptions&, CameraDesc&) { s.methods = MethodChoice::most_robust; }},
      {"all_two_sided", [](RenderSettings&, SceneBuildOptions& b, CameraDesc&) { b.all_two_sided ^= true; }},
      {"angle", [](RenderSettings&, SceneBuildOptions&, CameraDesc& c) { c.angle_degrees += 1.f; }},
  };
  for (const auto& [what, change] : changes) {
    RenderSettings s = settings;
    SceneBuildOptions b = build;
    CameraDesc c = camera;
    change(s, b, c);
    EXPECT_NE(render_fingerprint(s, b, std::nullopt, c, inputs, "1"), base) << what;
  }
  for (int point = 0; point < 3; ++point) {
    for (int axis = 0; axis < 3; ++axis) {
      CameraDesc c = camera;
      Vec3<float>& v = point == 0 ? c.from : point == 1 ? c.at : c.up;
      v[axis] += 0.25f;
      EXPECT_NE(render_fingerprint(settings, build, std::nullopt, c, inputs, "1"), base) << point << ", " << axis;
    }
  }
  // A crease angle given, and its value.
  const std::uint64_t creased = render_fingerprint(settings, build, 0.0, camera, inputs, "1");
  EXPECT_NE(creased, base);
  EXPECT_NE(render_fingerprint(settings, build, 45.0, camera, inputs, "1"), creased);
}

}  // namespace
}  // namespace quiver
