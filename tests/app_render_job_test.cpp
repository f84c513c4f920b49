// The render job's pieces a user sees (app/render_job.h): the one-line
// summary a render prints, the output name chosen for a scene, and the
// exit code and message of a failure.
#include "app/render_job.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <functional>
#include <new>
#include <stdexcept>
#include <utility>
#include <memory>
#include <string>

namespace quiver {
namespace {

// What print_render_summary writes, read back from a temporary file.
std::string summary_of(const RenderResult& result, const RenderSettings& settings, double load_ms, double build_ms) {
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::tmpfile(), &std::fclose);
  if (!file) throw std::runtime_error("no temporary file");
  print_render_summary(file.get(), result, settings, load_ms, build_ms, "out dir/image.png", "3 threads");
  std::rewind(file.get());
  std::string text;
  for (int c; (c = std::fgetc(file.get())) != EOF;) text += static_cast<char>(c);
  return text;
}

TEST(RenderSummary, SaysSizeTimeRaysRateAndOutput) {
  RenderResult result;
  result.stats.rays.primary = 3'000'000;
  result.stats.rays.shadow = 1'500'000;
  result.stats.rays.reflection = 400'000;
  result.stats.rays.refraction = 100'000;
  result.render_ms = 2000.0;
  RenderSettings settings;
  settings.width = 320;
  settings.height = 200;
  const std::string text = summary_of(result, settings, 1.5, 2.5);
  EXPECT_NE(text.find("rendered 320x200 ("), std::string::npos) << text;
  EXPECT_NE(text.find(", 3 threads) in 2.000 s: 5000000 rays, 2.50 Mrays/s (load 1.5 ms, build 2.5 ms) -> "
                      "out dir/image.png\n"),
            std::string::npos)
      << text;
}

TEST(RenderSummary, NoTimeGivesNoRate) {
  RenderResult result;
  result.stats.rays.primary = 10;
  RenderSettings settings;
  EXPECT_NE(summary_of(result, settings, 0.0, 0.0).find("in 0.000 s: 10 rays, 0.00 Mrays/s"), std::string::npos);
}

// The exit code and message of the exception being handled.
std::pair<int, std::string> described(const std::function<void()>& fail) {
  try {
    fail();
  } catch (...) {
    return describe_current_exception();
  }
  return {0, "nothing thrown"};
}

TEST(DescribeCurrentException, UsageErrorsExitTwoOthersOne) {
  EXPECT_EQ(described([] { throw UsageError("--width: expected a positive integer"); }),
            std::make_pair(kExitUsage, std::string("--width: expected a positive integer")));
  EXPECT_EQ(described([] { throw std::bad_alloc(); }), std::make_pair(kExitFailure, std::string("out of memory")));
  EXPECT_EQ(described([] { throw std::runtime_error("scene.nff:3:1: expected a number, found 'x'"); }),
            std::make_pair(kExitFailure, std::string("scene.nff:3:1: expected a number, found 'x'")));
  EXPECT_EQ(kExitUsage, 2);
  EXPECT_EQ(kExitFailure, 1);
}

TEST(DefaultOutput, TheScenesStemAsPngInTheWorkingDirectory) {
  EXPECT_EQ(default_output(""), "quiver.png");
  EXPECT_EQ(default_output("scenes/balls.nff"), "balls.png");
  EXPECT_EQ(default_output("/data/model.v2.obj"), "model.v2.png");
}

// The stats JSON names the built scene's stores and its acceleration
// structure apart, each as the scene counts it.
TEST(RenderStats, MemoryIsTheBuiltScenesStoresAndAcceleration) {
  RenderArgs args;
  args.output = (std::filesystem::temp_directory_path() / "quiver_render_stats_test.png").string();
  const CheckedRenderArgs checked = check_render_args(args, nullptr);
  const PreparedRender prepared = prepare_render(args, checked);
  ASSERT_NE(prepared.scene.memory_bytes(), prepared.scene.acceleration_bytes());
  const nlohmann::json stats = render_stats(args, checked, prepared, RenderResult{});
  EXPECT_EQ(stats.at("memory_bytes").at("scene"), prepared.scene.memory_bytes());
  EXPECT_EQ(stats.at("memory_bytes").at("acceleration"), prepared.scene.acceleration_bytes());
}

}  // namespace
}  // namespace quiver
