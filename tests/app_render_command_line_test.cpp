// The `quiver render` command of a view (app/render_command_line.h): its
// words read back through the CLI's own flags (app/render_flags_cli.h) to
// the same options, every number to the same bits; flags not set are left
// out; and the shell quoting is what a POSIX shell undoes.
#include "app/render_command_line.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "support/render_command_parse.h"

namespace quiver {
namespace {

using testing::parse_render_command;

void expect_same_bits(const std::optional<Vec3<float>>& read, const Vec3<float>& written) {
  ASSERT_TRUE(read.has_value());
  EXPECT_EQ(read->x, written.x);
  EXPECT_EQ(read->y, written.y);
  EXPECT_EQ(read->z, written.z);
}

TEST(RenderCommandLine, EveryOptionReadsBackToTheSameValues) {
  RenderOptions options;
  options.camera.look_from = Vec3<float>{-1.f / 3.f, 1e-7f, 12345.678f};
  options.camera.look_at = Vec3<float>{-0.f, -2.5e-3f, 0.1f};
  options.camera.up = Vec3<float>{0.f, 0.70710677f, -0.70710677f};
  options.camera.fov = 37.123456789012345;
  options.width = 641;
  options.height = 359;
  options.aa = parse_aa_flag("refine:0.0123:8");
  options.max_depth = 7;
  options.min_weight = 0.001;
  options.seed = 12345678901234567ull;
  options.filter_textures = false;
  options.crease_angle = 33.3;
  options.two_sided = true;
  options.robust_methods = true;
  options.strict = true;
  options.allow_outside_paths = true;
  options.aov = parse_aov_list("id,depth");
  options.threads = 3;
  options.simd = "scalar";

  const RenderArgs args = parse_render_command(render_command_words("my scenes/a'b.nff", options, "out dir/x.exr"));
  EXPECT_EQ(args.scene, "my scenes/a'b.nff");
  EXPECT_EQ(args.output, "out dir/x.exr");
  const RenderOptions& read = args.options;
  expect_same_bits(read.camera.look_from, *options.camera.look_from);
  expect_same_bits(read.camera.look_at, *options.camera.look_at);
  expect_same_bits(read.camera.up, *options.camera.up);
  EXPECT_EQ(read.camera.fov, options.camera.fov);
  EXPECT_EQ(read.width, options.width);
  EXPECT_EQ(read.height, options.height);
  ASSERT_TRUE(read.aa.has_value());
  EXPECT_EQ(to_string(*read.aa), "refine:0.0123:8");
  EXPECT_EQ(read.aa->threshold, options.aa->threshold);
  EXPECT_EQ(read.max_depth, options.max_depth);
  EXPECT_EQ(read.min_weight, options.min_weight);
  EXPECT_EQ(read.seed, options.seed);
  EXPECT_EQ(read.filter_textures, options.filter_textures);
  EXPECT_EQ(read.crease_angle, options.crease_angle);
  EXPECT_TRUE(read.two_sided && read.robust_methods && read.strict && read.allow_outside_paths);
  ASSERT_TRUE(read.aov.has_value());
  EXPECT_TRUE(read.aov->depth && read.aov->id && !read.aov->normal);
  EXPECT_EQ(read.threads, 3);
  EXPECT_EQ(read.simd, options.simd);
  EXPECT_FALSE(read.preset_spd);
}

// Numbers are written to the digits that read back to them: a small minimum
// weight does not become 0, nor a long one lose its tail.
TEST(RenderCommandLine, SmallAndLongNumbersReadBackToTheSameBits) {
  RenderOptions options;
  for (const double weight : {1e-7, 0.0012345678901234, 2.5e-300}) {
    options.min_weight = weight;
    options.crease_angle = 180.0 / 7.0;
    const RenderOptions read = parse_render_command(render_command_words("", options, "x.png")).options;
    EXPECT_EQ(read.min_weight, weight);
    EXPECT_EQ(read.crease_angle, options.crease_angle);
  }
}

// Seed 0 is the default and left out; every other seed, 1 among them, is said.
TEST(RenderCommandLine, EverySeedButTheDefaultIsSaid) {
  RenderOptions options;
  for (const std::uint64_t seed : {1ull, 2ull, 18446744073709551615ull}) {
    options.seed = seed;
    EXPECT_EQ(parse_render_command(render_command_words("", options, "x.png")).options.seed, seed);
  }
  options.seed = 0;
  const std::vector<std::string> words = render_command_words("", options, "x.png");
  EXPECT_EQ(std::find(words.begin(), words.end(), "--seed"), words.end());
}

TEST(RenderCommandLine, LeavesOutWhatIsNotSet) {
  EXPECT_EQ(render_command_words("", RenderOptions{}, "quiver.png"),
            (std::vector<std::string>{"quiver", "render", "-o", "quiver.png"}));
  RenderOptions spd;
  spd.preset_spd = true;
  spd.width = 64;
  const std::vector<std::string> words = render_command_words("balls.nff", spd, "balls.png");
  EXPECT_EQ(words, (std::vector<std::string>{"quiver", "render", "balls.nff", "--width", "64", "--preset", "spd", "-o",
                                             "balls.png"}));
  EXPECT_TRUE(parse_render_command(words).options.preset_spd);
}

// The words a POSIX shell makes of a line: /bin/sh prints each on a line of its own.
std::vector<std::string> shell_words(const std::string& line) {
  const std::string script = "printf '%s\\n' " + line;
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> pipe(::popen(("/bin/sh -c " + shell_quoted(script)).c_str(), "r"),
                                                            &::pclose);
  if (!pipe) return {};
  std::vector<std::string> words;
  std::string word;
  for (int c; (c = std::fgetc(pipe.get())) != EOF;) {
    if (c == '\n') {
      words.push_back(word);
      word.clear();
    } else {
      word += static_cast<char>(c);
    }
  }
  return words;
}

TEST(ShellQuoting, PlainWordsStayAsTheyAreAndOthersReadBack) {
  EXPECT_EQ(shell_quoted("--look-from=-1.5,2e-07,3"), "--look-from=-1.5,2e-07,3");
  EXPECT_EQ(shell_quoted("scenes/balls.nff"), "scenes/balls.nff");
  EXPECT_EQ(shell_quoted("a b"), "'a b'");
  EXPECT_EQ(shell_quoted(""), "''");
  EXPECT_EQ(shell_quoted("it's"), "'it'\\''s'");
  const std::vector<std::string> words{"quiver", "it's", "a b", "", "$HOME", "`ls`", "*", "x;y", "back\\slash", "~"};
  EXPECT_EQ(shell_words(shell_command_line(words)), words);
}

}  // namespace
}  // namespace quiver
