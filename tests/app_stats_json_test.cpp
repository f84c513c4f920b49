// The render statistics JSON (app/stats_json.h): every key present, values
// consistent with a hand-made RenderResult (total = sum of kinds,
// utilisation = active / issued), and the atomic file write.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "app/stats_json.h"

namespace quiver {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct Example {
  RenderResult result;
  RenderSettings settings;
  RenderStatsContext context;
};

Example example() {
  Example e;
  e.result.image = Framebuffer(4, 3);
  e.result.image.depth.assign(12, 1.f);
  e.result.render_ms = 2.5;
  e.result.threads = 3;
  RayCounts& rays = e.result.stats.rays;
  rays.primary = 1000;
  rays.primary_hits = 800;
  rays.shadow = 700;
  rays.reflection = 300;
  rays.refraction = 111;
  e.result.stats.waves = {{1000, 1000, 1000}, {411, 416, 600}, {0, 0, 0}};
  e.result.stats.shadow = {700, 704, 1200};
  e.result.stats.shading_active = 1100;
  e.result.stats.light_sample_active = 700;
  e.result.stats.light_sample_issued = 960;
  e.settings.width = 4;
  e.settings.height = 3;
  e.settings.aa = parse_anti_aliasing("adaptive:0.125:3");
  e.settings.trace.max_depth = 7;
  e.settings.trace.min_weight = 0.25f;
  e.settings.trace.seed = 0xFFFFFFFFFFFFFFFFull;
  e.settings.isa = Isa::scalar;
  e.settings.aov_depth = true;
  e.context.version = "9.8.7";
  e.context.scene = "scene.nff";
  e.context.output = "out.exr";
  e.context.load_ms = 1.5;
  e.context.build_ms = 0.75;
  e.context.scene_memory_bytes = 4242;
  e.context.acceleration_memory_bytes = 1717;
  return e;
}

void expect_utilization(const json& value, std::uint64_t active, std::uint64_t issued) {
  if (issued == 0) {
    EXPECT_TRUE(value.is_null());
  } else {
    EXPECT_DOUBLE_EQ(value.get<double>(), double(active) / double(issued));
  }
}

TEST(StatsJson, SettingsAndTimings) {
  const Example e = example();
  const json j = render_stats_json(e.result, e.settings, e.context);
  EXPECT_EQ(j.at("version"), "9.8.7");
  EXPECT_EQ(j.at("scene"), "scene.nff");
  EXPECT_EQ(j.at("output"), "out.exr");
  EXPECT_EQ(j.at("load_ms"), 1.5);
  EXPECT_EQ(j.at("build_ms"), 0.75);
  EXPECT_EQ(j.at("render_ms"), 2.5);
  EXPECT_EQ(j.at("threads"), 3);
  EXPECT_EQ(j.at("simd"), "scalar");
  EXPECT_EQ(j.at("kernel_unit"), std::string(kernel_unit_name(kernel_unit_for(Isa::scalar))));
  EXPECT_EQ(j.at("sphere_method"), "robust");
  EXPECT_EQ(j.at("lanes"), 1);
  EXPECT_EQ(j.at("width"), 4);
  EXPECT_EQ(j.at("height"), 3);
  EXPECT_EQ(j.at("aa"), "adaptive:0.125:3");
  EXPECT_EQ(j.at("max_depth"), 7);
  EXPECT_EQ(j.at("min_weight").get<float>(), 0.25f);
  EXPECT_EQ(j.at("seed").get<std::uint64_t>(), 0xFFFFFFFFFFFFFFFFull);
  EXPECT_EQ(j.at("aovs"), json::array({"depth"}));
}

TEST(StatsJson, RayCountsAndRate) {
  const Example e = example();
  const json j = render_stats_json(e.result, e.settings, e.context);
  const json& rays = j.at("rays");
  const RayCounts& r = e.result.stats.rays;
  EXPECT_EQ(rays.at("primary"), r.primary);
  EXPECT_EQ(rays.at("eye_hit"), r.primary_hits);
  EXPECT_EQ(rays.at("shadow"), r.shadow);
  EXPECT_EQ(rays.at("reflection"), r.reflection);
  EXPECT_EQ(rays.at("refraction"), r.refraction);
  const std::uint64_t sum = rays.at("primary").get<std::uint64_t>() + rays.at("shadow").get<std::uint64_t>() +
                            rays.at("reflection").get<std::uint64_t>() + rays.at("refraction").get<std::uint64_t>();
  EXPECT_EQ(rays.at("total").get<std::uint64_t>(), sum);
  EXPECT_EQ(sum, 2111u);
  EXPECT_DOUBLE_EQ(j.at("mrays_per_s").get<double>(), double(sum) / (2.5 / 1000.0) / 1e6);

  Example zero_time = example();
  zero_time.result.render_ms = 0.0;
  EXPECT_TRUE(render_stats_json(zero_time.result, zero_time.settings, zero_time.context).at("mrays_per_s").is_null());
}

TEST(StatsJson, PhaseTimesInMilliseconds) {
  Example e = example();
  e.result.stats.phases = {1'500'000, 250'000, 3'000'000, 7, 5};
  const json stats = render_stats_json(e.result, e.settings, e.context);
  const json& phases = stats.at("phases_ms");
  EXPECT_DOUBLE_EQ(phases.at("camera_and_film").get<double>(), 1.5);
  EXPECT_DOUBLE_EQ(phases.at("intersection").get<double>(), 0.25);
  EXPECT_DOUBLE_EQ(phases.at("shading").get<double>(), 3.0);
  EXPECT_DOUBLE_EQ(phases.at("shadows").get<double>(), 7e-6);
  EXPECT_EQ(phases.size(), 4u);
  // The walks: all of intersection and the shadow walks' part of shadows.
  EXPECT_DOUBLE_EQ(stats.at("traversal_ms").get<double>(), 0.250005);
  EXPECT_EQ(stats.at("thread_time_keys"), json({"phases_ms", "traversal_ms"}));
}

TEST(StatsJson, LaneUtilizationIsActiveOverIssued) {
  const Example e = example();
  const json lanes = render_stats_json(e.result, e.settings, e.context).at("lane_utilization");
  const json& waves = lanes.at("waves");
  ASSERT_EQ(waves.size(), e.result.stats.waves.size());
  WaveLanes overall = e.result.stats.shadow;
  for (std::size_t d = 0; d < waves.size(); ++d) {
    const WaveLanes& w = e.result.stats.waves[d];
    SCOPED_TRACE(d);
    EXPECT_EQ(waves[d].at("depth"), d);
    EXPECT_EQ(waves[d].at("active"), w.active);
    EXPECT_EQ(waves[d].at("issued_compacted"), w.issued_compacted);
    EXPECT_EQ(waves[d].at("issued_uncompacted"), w.issued_uncompacted);
    expect_utilization(waves[d].at("utilization_compacted"), w.active, w.issued_compacted);
    expect_utilization(waves[d].at("utilization_uncompacted"), w.active, w.issued_uncompacted);
    overall.active += w.active;
    overall.issued_compacted += w.issued_compacted;
    overall.issued_uncompacted += w.issued_uncompacted;
  }
  const WaveLanes& s = e.result.stats.shadow;
  const json& shadow = lanes.at("shadow");
  EXPECT_EQ(shadow.at("active"), s.active);
  EXPECT_EQ(shadow.at("issued_compacted"), s.issued_compacted);
  EXPECT_EQ(shadow.at("issued_uncompacted"), s.issued_uncompacted);
  expect_utilization(shadow.at("utilization_compacted"), s.active, s.issued_compacted);
  expect_utilization(shadow.at("utilization_uncompacted"), s.active, s.issued_uncompacted);
  // The shading packets issue what the waves issue; their active lanes are the hits.
  const json& shading = lanes.at("shading");
  EXPECT_EQ(shading.at("active"), 1100u);
  EXPECT_EQ(shading.at("issued_compacted"), overall.issued_compacted - s.issued_compacted);
  EXPECT_EQ(shading.at("issued_uncompacted"), overall.issued_uncompacted - s.issued_uncompacted);
  expect_utilization(shading.at("utilization_compacted"), 1100u, overall.issued_compacted - s.issued_compacted);
  const json& light = lanes.at("light_samples");
  EXPECT_EQ(light.at("active"), 700u);
  EXPECT_EQ(light.at("issued"), 960u);
  expect_utilization(light.at("utilization"), 700u, 960u);
  const json& all = lanes.at("overall");
  EXPECT_EQ(all.at("active"), overall.active);
  EXPECT_EQ(all.at("issued_compacted"), overall.issued_compacted);
  EXPECT_EQ(all.at("issued_uncompacted"), overall.issued_uncompacted);
  expect_utilization(all.at("compacted"), overall.active, overall.issued_compacted);
  expect_utilization(all.at("uncompacted"), overall.active, overall.issued_uncompacted);
  EXPECT_TRUE(waves[2].at("utilization_compacted").is_null());  // the empty wave
}

TEST(StatsJson, MemoryBytes) {
  Example e = example();
  // Every AOV, so that each buffer's bytes are counted.
  Framebuffer& f = e.result.image;
  f.normal.assign(36, 0.f);
  f.kind.assign(12, 0);
  f.id.assign(12, 0);
  const json memory = render_stats_json(e.result, e.settings, e.context).at("memory_bytes");
  EXPECT_EQ(memory.at("scene"), 4242u);
  EXPECT_EQ(memory.at("acceleration"), 1717u);
  const std::size_t expected = (f.rgb.capacity() + f.depth.capacity() + f.normal.capacity()) * sizeof(float) +
                               (f.kind.capacity() + f.id.capacity()) * sizeof(std::int32_t);
  EXPECT_GE(expected, (12u * 3u + 12u + 36u) * sizeof(float) + 24u * sizeof(std::int32_t));
  EXPECT_EQ(memory.at("framebuffer"), expected);
}

class StatsFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("quiver_stats_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::size_t entries() const {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir_)) ++n;
    return n;
  }
  fs::path dir_;
};

// stage_json_file and commit, as the CLI writes a stats file.
void write_json_file(const fs::path& path, const json& value) {
  StagedOutputs outputs;
  stage_json_file(outputs, path, value);
  outputs.commit();
}

TEST_F(StatsFile, WritesParsableJsonAndNoTemporaryFile) {
  const Example e = example();
  const json j = render_stats_json(e.result, e.settings, e.context);
  const fs::path path = dir_ / "stats.json";
  write_json_file(path, j);
  std::ifstream in(path);
  const json back = json::parse(in);
  EXPECT_EQ(back, j);
  EXPECT_EQ(entries(), 1u);
  // Overwrites an existing file.
  write_json_file(path, json{{"replaced", true}});
  std::ifstream again(path);
  EXPECT_EQ(json::parse(again), (json{{"replaced", true}}));
  EXPECT_EQ(entries(), 1u);
}

TEST_F(StatsFile, BadPathsThrowAndCreateNothing) {
  EXPECT_THROW(write_json_file(dir_ / "missing" / "stats.json", json{}), std::runtime_error);
  EXPECT_THROW(check_stats_path(dir_ / "missing" / "stats.json"), std::runtime_error);
  fs::create_directory(dir_ / "a_directory");
  EXPECT_THROW(write_json_file(dir_ / "a_directory", json{}), std::runtime_error);
  EXPECT_THROW(check_stats_path(dir_ / "a_directory"), std::runtime_error);
  std::ofstream(dir_ / "plain_file") << "x";
  EXPECT_THROW(check_stats_path(dir_ / "plain_file" / "stats.json"), std::runtime_error);
  EXPECT_EQ(entries(), 2u);  // a_directory and plain_file only
  EXPECT_NO_THROW(check_stats_path(dir_ / "new.json"));
  EXPECT_FALSE(fs::exists(dir_ / "new.json"));
}

}  // namespace
}  // namespace quiver
