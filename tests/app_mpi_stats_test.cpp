// quiver-mpi's rank reports and merged stats (app/mpi_stats.h): a report
// survives its bytes; idle time, efficiency and the tile counts add up.
#include <cstddef>
#include <span>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "app/mpi_stats.h"

namespace quiver {
namespace {

RankReport report(int threads, std::uint64_t tiles, double busy_ms, std::uint64_t primary) {
  RankReport r;
  r.threads = threads;
  r.tiles = tiles;
  r.tiles_repeated = 1;
  r.render_ms = 100.0;
  r.busy_ms = busy_ms;
  r.start_ms = 31.25;
  r.stats.rays = {primary, primary / 2, 3 * primary, 7, 5};
  r.stats.phases = {1, 2, 3, 4, 5};
  r.stats.waves = {{10, 16, 24}, {4, 8, 8}};
  r.stats.shadow = {9, 10, 11};
  r.stats.shading_active = 12;
  r.stats.light_sample_active = 13;
  r.stats.light_sample_issued = 14;
  return r;
}

TEST(MpiStats, ARankReportSurvivesItsBytes) {
  const RankReport r = report(3, 40, 250.5, 1000);
  const RankReport back = decode_rank_report(encode_rank_report(r));
  EXPECT_EQ(back.threads, 3);
  EXPECT_EQ(back.tiles, 40u);
  EXPECT_EQ(back.tiles_repeated, 1u);
  EXPECT_EQ(back.busy_ms, 250.5);
  EXPECT_EQ(back.start_ms, 31.25);
  EXPECT_EQ(back.render_ms, 100.0);
  EXPECT_EQ(back.stats.rays.shadow, 3000u);
  EXPECT_EQ(back.stats.rays.primary_hits, 500u);
  EXPECT_EQ(back.stats.phases.shadows, 4u);
  EXPECT_EQ(back.stats.phases.shadow_walks, 5u);
  ASSERT_EQ(back.stats.waves.size(), 2u);
  for (std::size_t d = 0; d < 2; ++d) {  // every field of every wave in its place
    EXPECT_EQ(back.stats.waves[d].active, r.stats.waves[d].active) << d;
    EXPECT_EQ(back.stats.waves[d].issued_compacted, r.stats.waves[d].issued_compacted) << d;
    EXPECT_EQ(back.stats.waves[d].issued_uncompacted, r.stats.waves[d].issued_uncompacted) << d;
  }
  EXPECT_EQ(back.stats.shadow.issued_uncompacted, 11u);
  EXPECT_EQ(back.stats.light_sample_issued, 14u);
  std::vector<std::byte> bytes = encode_rank_report(r);
  bytes.resize(bytes.size() - 8);
  EXPECT_THROW(decode_rank_report(bytes), std::invalid_argument);
  EXPECT_THROW(decode_rank_report(std::vector<std::byte>(3)), std::invalid_argument);
  // Shorter than its fixed part (a report without waves): the size is wrong, nothing past it is read.
  const std::vector<std::byte> no_waves = encode_rank_report(RankReport{});
  EXPECT_EQ(decode_rank_report(no_waves).stats.waves.size(), 0u);
  for (std::size_t words = 0; words < no_waves.size() / 8; ++words) {
    try {
      decode_rank_report(std::span(no_waves).first(8 * words));
      ADD_FAILURE() << words << " words were read as a report";
    } catch (const std::invalid_argument& error) {
      EXPECT_STREQ(error.what(), "rank report: wrong size") << words << " words";
    }
  }
}

TEST(MpiStats, EfficiencyIsBusyTimeOverEveryThreadsTimeAndRaysAddUp) {
  MpiJobSummary job;
  job.tiles = 100;
  job.tiles_resumed = 20;
  job.render_ms = 200.0;
  job.ranks = {report(1, 30, 180.0, 1000), report(2, 50, 360.0, 3000)};
  const nlohmann::json j = mpi_stats_json(job);
  EXPECT_EQ(j["ranks"], 2);
  EXPECT_EQ(j["tiles_rendered"], 80);
  EXPECT_EQ(j["tiles_repeated"], 2);
  EXPECT_EQ(j["tiles_resumed"], 20);
  EXPECT_DOUBLE_EQ(j["efficiency"].get<double>(), (180.0 + 360.0) / (3 * 200.0));
  EXPECT_DOUBLE_EQ(j["per_rank"][0]["idle_ms"].get<double>(), 20.0);
  EXPECT_DOUBLE_EQ(j["per_rank"][1]["idle_ms"].get<double>(), 40.0);
  EXPECT_EQ(j["per_rank"][1]["start_ms"].get<double>(), 31.25);
  EXPECT_EQ(j["per_rank"][1]["rays"]["total"], 3000 + 9000 + 7 + 5);
  const TraceStats merged = merged_trace_stats(job.ranks);
  EXPECT_EQ(merged.rays.primary, 4000u);
  EXPECT_EQ(merged.waves[0].active, 20u);
}

}  // namespace
}  // namespace quiver
