// A render's counters (integrator/trace_stats.h): adding one thread's or
// tile's counts to another's sums every counter, phase time and wave, each
// into its own field.
#include "integrator/trace_stats.h"

#include <cstdint>

#include <gtest/gtest.h>

namespace quiver {
namespace {

// Every field a different value from `base` on, so a field added into
// another or taken from another shows.
TraceStats numbered(std::uint64_t base, std::size_t waves) {
  std::uint64_t next = base;
  TraceStats s;
  s.rays = {next++, next++, next++, next++, next++};
  s.phases = {next++, next++, next++, next++, next++};
  for (std::size_t d = 0; d < waves; ++d) s.waves.push_back({next++, next++, next++});
  s.shadow = {next++, next++, next++};
  s.shading_active = next++;
  s.light_sample_active = next++;
  s.light_sample_issued = next++;
  return s;
}

void expect_sum(const WaveLanes& sum, const WaveLanes& a, const WaveLanes& b, const char* what) {
  EXPECT_EQ(sum.active, a.active + b.active) << what;
  EXPECT_EQ(sum.issued_compacted, a.issued_compacted + b.issued_compacted) << what;
  EXPECT_EQ(sum.issued_uncompacted, a.issued_uncompacted + b.issued_uncompacted) << what;
}

TEST(TraceStats, AddingSumsEveryCounterPhaseAndWaveIntoItsOwn) {
  const TraceStats a = numbered(100, 1), b = numbered(1000, 3);
  TraceStats sum = a;
  sum.add(b);
  EXPECT_EQ(sum.rays.primary, a.rays.primary + b.rays.primary);
  EXPECT_EQ(sum.rays.primary_hits, a.rays.primary_hits + b.rays.primary_hits);
  EXPECT_EQ(sum.rays.shadow, a.rays.shadow + b.rays.shadow);
  EXPECT_EQ(sum.rays.reflection, a.rays.reflection + b.rays.reflection);
  EXPECT_EQ(sum.rays.refraction, a.rays.refraction + b.rays.refraction);
  EXPECT_EQ(sum.phases.camera_and_film, a.phases.camera_and_film + b.phases.camera_and_film);
  EXPECT_EQ(sum.phases.intersection, a.phases.intersection + b.phases.intersection);
  EXPECT_EQ(sum.phases.shading, a.phases.shading + b.phases.shading);
  EXPECT_EQ(sum.phases.shadows, a.phases.shadows + b.phases.shadows);
  EXPECT_EQ(sum.phases.shadow_walks, a.phases.shadow_walks + b.phases.shadow_walks);
  EXPECT_EQ(sum.shading_active, a.shading_active + b.shading_active);
  EXPECT_EQ(sum.light_sample_active, a.light_sample_active + b.light_sample_active);
  EXPECT_EQ(sum.light_sample_issued, a.light_sample_issued + b.light_sample_issued);
  expect_sum(sum.shadow, a.shadow, b.shadow, "shadow");
  ASSERT_EQ(sum.waves.size(), 3u);  // the deeper list's depths, the shorter's added in
  expect_sum(sum.waves[0], a.waves[0], b.waves[0], "wave 0");
  expect_sum(sum.waves[1], WaveLanes{}, b.waves[1], "wave 1");
  expect_sum(sum.waves[2], WaveLanes{}, b.waves[2], "wave 2");
}

}  // namespace
}  // namespace quiver
