#include "tests/support/kernel_checks.h"

#include <bit>
#include <cstdint>
#include <sstream>

namespace quiver::testing {

namespace {
bool same_bits(float a, float b) { return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b); }

std::string describe(const Hit<float>& h) {
  std::ostringstream s;
  s.precision(9);
  s << "{t=" << h.t << " u=" << h.u << " v=" << h.v << " ng=(" << h.ng.x << ", " << h.ng.y << ", " << h.ng.z
    << ") id=" << h.id << "}";
  return s.str();
}
}  // namespace

::testing::AssertionResult hits_bit_equal(const HitSoA& expected, const HitSoA& actual) {
  if (expected.count != actual.count) {
    return ::testing::AssertionFailure() << "counts differ: " << expected.count << " vs " << actual.count;
  }
  for (std::size_t i = 0; i < expected.count; ++i) {
    const Hit<float> e = expected.get(i), a = actual.get(i);
    if (!same_bits(e.t, a.t) || !same_bits(e.u, a.u) || !same_bits(e.v, a.v) || !same_bits(e.ng.x, a.ng.x) ||
        !same_bits(e.ng.y, a.ng.y) || !same_bits(e.ng.z, a.ng.z) || e.id != a.id) {
      return ::testing::AssertionFailure() << "ray " << i << ": expected " << describe(e) << ", got "
                                           << describe(a);
    }
  }
  return ::testing::AssertionSuccess();
}

::testing::AssertionResult occlusion_equal(const OcclusionSoA& expected, const OcclusionSoA& actual) {
  for (std::size_t i = 0; i < expected.count; ++i) {
    if (expected.occluded[i] != actual.occluded[i]) {
      return ::testing::AssertionFailure() << "ray " << i << ": expected occluded=" << expected.occluded[i]
                                           << ", got " << actual.occluded[i];
    }
  }
  return ::testing::AssertionSuccess();
}

::testing::AssertionResult occlusion_matches_hits(const OcclusionSoA& occlusion, const HitSoA& hits) {
  for (std::size_t i = 0; i < hits.count; ++i) {
    if ((occlusion.occluded[i] != 0) != (hits.id[i] != kNoHit)) {
      return ::testing::AssertionFailure() << "ray " << i << ": any-hit says " << occlusion.occluded[i]
                                           << " but closest-hit id is " << hits.id[i];
    }
  }
  return ::testing::AssertionSuccess();
}

void expect_results_match_scalar(const StreamResults& ref, const StreamResults& got) {
  EXPECT_TRUE(hits_bit_equal(ref.closest_packets, ref.closest_scan)) << "scalar scan vs scalar packets";
  EXPECT_TRUE(hits_bit_equal(ref.closest_packets, got.closest_packets)) << "packets vs scalar";
  EXPECT_TRUE(hits_bit_equal(ref.closest_packets, got.closest_scan)) << "scan vs scalar";
  EXPECT_TRUE(occlusion_equal(ref.occluded_packets, got.occluded_packets)) << "any-hit packets vs scalar";
  EXPECT_TRUE(occlusion_equal(ref.occluded_packets, got.occluded_scan)) << "any-hit scan vs scalar";
  EXPECT_TRUE(hits_bit_equal(ref.closest_packets, got.closest_within)) << "packets within the store's box vs scalar";
  EXPECT_TRUE(occlusion_equal(ref.occluded_packets, got.occluded_within))
      << "any-hit packets within the store's box vs scalar";
  EXPECT_TRUE(occlusion_matches_hits(ref.occluded_packets, ref.closest_packets));
}

}  // namespace quiver::testing
