// Checks shared by every kernel's tests: bit-exact comparison of stream
// results and the typed fixture over lane widths 1, 4, 8 and 16.
#pragma once

#include <type_traits>

#include <gtest/gtest.h>

#include "geometry/primitive_bounds.h"
#include "geometry/streams.h"
#include "simd/isa.h"
#include "tests/support/ray_sampling.h"

namespace quiver::testing {

// Every ray's t, u, v, ng and id equal bit for bit (first difference shown).
::testing::AssertionResult hits_bit_equal(const HitSoA& expected, const HitSoA& actual);
::testing::AssertionResult occlusion_equal(const OcclusionSoA& expected, const OcclusionSoA& actual);
// Any-hit agrees with closest-hit: occluded iff a closest hit exists.
::testing::AssertionResult occlusion_matches_hits(const OcclusionSoA& occlusion, const HitSoA& hits);

// Every kernel unit; each is compared with the portable scalar unit.
using KernelUnits = OverKernelUnits<::testing::Types>;

// Typed fixture: skips, saying why, only when this CPU cannot run the unit.
template <class U>
class UnitTest : public ::testing::Test {
 protected:
  static constexpr KernelUnit kUnit = U::value;
  void SetUp() override {
    if (!kernel_unit_supported(kUnit)) {
      GTEST_SKIP() << "this CPU cannot run the " << kernel_unit_name(kUnit) << " kernel unit";
    }
  }
};

// The closest hit of one ray through a stream set's packet stream.
template <class S>
Hit<float> closest_hit(const KernelStreams<S>& streams, const Ray<float>& ray, const S& prims) {
  const RaySoA rays = to_soa(std::vector<Ray<float>>{ray});
  HitSoA hits(rays);
  streams.closest_packets(rays, prims, hits);
  return hits.get(0);
}

struct StreamResults {
  HitSoA closest_packets, closest_scan, closest_within;
  OcclusionSoA occluded_packets, occluded_scan, occluded_within;
};

// Runs every stream the kernel has (a missing scan is left as packets; the
// packets within the store's box, for bounded kinds, else as packets).
template <class S>
StreamResults run_streams(const KernelStreams<S>& streams, const RaySoA& rays, const S& prims) {
  StreamResults r{HitSoA(rays), HitSoA(rays), HitSoA(rays), OcclusionSoA(rays), OcclusionSoA(rays), OcclusionSoA(rays)};
  streams.closest_packets(rays, prims, r.closest_packets);
  streams.occluded_packets(rays, prims, r.occluded_packets);
  if (streams.closest_scan) {
    streams.closest_scan(rays, prims, r.closest_scan);
    streams.occluded_scan(rays, prims, r.occluded_scan);
  } else {
    r.closest_scan = r.closest_packets;
    r.occluded_scan = r.occluded_packets;
  }
  r.closest_within = r.closest_packets;
  r.occluded_within = r.occluded_packets;
  if constexpr (requires { primitive_box(prims, std::size_t(0)); }) {
    const Box bounds = store_box(prims);
    r.closest_within = HitSoA(rays);
    r.occluded_within = OcclusionSoA(rays);
    streams.closest_packets_within(rays, prims, bounds, r.closest_within);
    streams.occluded_packets_within(rays, prims, bounds, r.occluded_within);
  }
  return r;
}

// A tested unit's results equal the scalar reference's bit for bit, in both
// orientations and culled by the store's box, and any-hit agrees with
// closest-hit.
void expect_results_match_scalar(const StreamResults& ref, const StreamResults& got);

// Runs the scalar and the tested streams and checks them with
// expect_results_match_scalar. Returns the scalar results for further checks.
template <class S>
StreamResults expect_streams_match_scalar(const KernelStreams<S>& scalar, const KernelStreams<S>& tested,
                                          const RaySoA& rays, const S& prims) {
  StreamResults ref = run_streams(scalar, rays, prims);
  expect_results_match_scalar(ref, run_streams(tested, rays, prims));
  return ref;
}

}  // namespace quiver::testing
