// refine:T:N's strata (integrator/refine_sampling.h): each level's samples
// lie in their strata with offsets of their own, a refined stratum's sample
// stays in the sub-stratum that holds it, and a pixel is uncertain exactly
// when its mean's standard error passes the threshold.
#include "integrator/refine_sampling.h"

#include <algorithm>
#include <cstdint>
#include <set>
#include <utility>

#include <gtest/gtest.h>

namespace quiver {
namespace {

constexpr std::uint64_t kSeed = 7;

// Jittered strata of sides 2, 4 and 8 in one pixel: each sample inside its
// stratum, and no two strata of any level share their offset within it
// (each level's offsets are hashed from numbers of its own).
TEST(RefineStrata, EachLevelsSamplesLieInTheirStrataWithOffsetsOfTheirOwn) {
  for (const std::uint64_t pixel : {std::uint64_t{0}, std::uint64_t{12345}}) {
    std::set<std::pair<double, double>> offsets;
    std::size_t strata = 0;
    for (int side : {2, 4, 8}) {
      for (int j = 0; j < side; ++j) {
        for (int i = 0; i < side; ++i) {
          const StratumSample s = refine_stratum(kSeed, pixel, side, i, j, AntiAliasing::Strata::jitter);
          EXPECT_EQ(s.i, i);
          EXPECT_EQ(s.j, j);
          EXPECT_GE(s.x * side, double(i));
          EXPECT_LT(s.x * side, double(i + 1));
          EXPECT_GE(s.y * side, double(j));
          EXPECT_LT(s.y * side, double(j + 1));
          offsets.insert({s.x * side - i, s.y * side - j});
          ++strata;
        }
      }
    }
    EXPECT_EQ(offsets.size(), strata) << "pixel " << pixel;
  }
  // Another pixel or seed draws other offsets; grid strata sit at the centres.
  const StratumSample a = refine_stratum(kSeed, 1, 4, 1, 2, AntiAliasing::Strata::jitter);
  const StratumSample b = refine_stratum(kSeed, 2, 4, 1, 2, AntiAliasing::Strata::jitter);
  const StratumSample c = refine_stratum(kSeed + 1, 1, 4, 1, 2, AntiAliasing::Strata::jitter);
  EXPECT_NE(a.x, b.x);
  EXPECT_NE(a.x, c.x);
  const StratumSample centre = refine_stratum(kSeed, 1, 4, 1, 2, AntiAliasing::Strata::grid);
  EXPECT_EQ(centre.x, 1.5 / 4);
  EXPECT_EQ(centre.y, 2.5 / 4);
}

// The sub-stratum named for a sample holds it, on both axes, for samples
// anywhere in their strata, the edges included.
TEST(RefineStrata, TheSubStratumNamedHoldsTheSample) {
  for (int side : {2, 4}) {
    const int child = 2 * side;
    for (int j = 0; j < side; ++j) {
      for (int i = 0; i < side; ++i) {
        for (const double u : {0.0, 0.1, 0.49, 0.5, 0.77, 0.999}) {
          for (const double v : {0.0, 0.3, 0.5, 0.93}) {
            const StratumSample s{i, j, (i + u) / side, (j + v) / side};
            const auto [ci, cj] = sub_stratum_holding(s, child);
            EXPECT_TRUE(ci == 2 * i || ci == 2 * i + 1);
            EXPECT_TRUE(cj == 2 * j || cj == 2 * j + 1);
            EXPECT_EQ(ci, 2 * i + (u < 0.5 ? 0 : 1)) << side << " " << i << " " << j << " " << u << " " << v;
            EXPECT_EQ(cj, 2 * j + (v < 0.5 ? 0 : 1)) << side << " " << i << " " << j << " " << u << " " << v;
          }
        }
      }
    }
  }
}

// Four samples 0, 0, 1, 1 in one channel: mean 1/2, unbiased variance 1/3,
// so the mean's standard error is sqrt(1/12) = 0.2887.
TEST(RefineStrata, UncertainExactlyWhenTheMeansStandardErrorPassesTheThreshold) {
  RefinedPixel px;
  for (const double value : {0.0, 0.0, 1.0, 1.0}) {
    px.clamped_sum = px.clamped_sum + Vec3<double>(0.0, value, 0.0);
    px.clamped_squares = px.clamped_squares + Vec3<double>(0.0, value * value, 0.0);
    ++px.count;
  }
  EXPECT_TRUE(too_uncertain(px, 0.28f));
  EXPECT_FALSE(too_uncertain(px, 0.29f));
  // Equal samples: no error, whatever the threshold.
  RefinedPixel flat;
  for (int k = 0; k < 4; ++k) {
    flat.clamped_sum = flat.clamped_sum + Vec3<double>(0.5, 0.5, 0.5);
    flat.clamped_squares = flat.clamped_squares + Vec3<double>(0.25, 0.25, 0.25);
    ++flat.count;
  }
  EXPECT_FALSE(too_uncertain(flat, 0.f));
}

}  // namespace
}  // namespace quiver
