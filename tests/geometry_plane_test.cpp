#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "geometry/plane_streams.h"
#include "tests/support/kernel_checks.h"
#include "bench/support/ray_sampling.h"

namespace quiver {
namespace {

using testing::RaySampler;

constexpr float kInf = std::numeric_limits<float>::infinity();

PlaneSoA planes_of(std::initializer_list<PlaneDesc> descs, BuildReport* out = nullptr) {
  BuildReport report;
  PlaneSoA soa = build_planes(std::vector<PlaneDesc>(descs), report);
  if (out) *out = report;
  return soa;
}

Hit<float> closest(const Ray<float>& ray, const PlaneSoA& planes) {
  return testing::closest_hit(plane_streams<KernelUnit::scalar>(PlaneMethod::seed), ray, planes);
}

TEST(PlaneKernel, HitsFloorStraightDown) {
  const PlaneSoA floor = planes_of({{{0, -1, 0}, {0, 2, 0}}});
  const Hit<float> h = closest({{0, 3, 0}, {0, -1, 0}, 0.f, kInf}, floor);
  ASSERT_EQ(h.id, 0);
  EXPECT_FLOAT_EQ(h.t, 4.f);
  EXPECT_FLOAT_EQ(h.ng.y, 1.f);
}

TEST(PlaneKernel, HitsFromBelowWithSameNormal) {
  const PlaneSoA floor = planes_of({{{0, 0, 0}, {0, 1, 0}}});
  const Hit<float> h = closest({{1, -2, 1}, {0, 2, 0}, 0.f, kInf}, floor);
  ASSERT_EQ(h.id, 0);
  EXPECT_FLOAT_EQ(h.t, 1.f);  // direction not normalised: t in its units
}

TEST(PlaneKernel, ParallelRayMissesEvenOnThePlane) {
  const PlaneSoA floor = planes_of({{{0, 0, 0}, {0, 1, 0}}});
  EXPECT_EQ(closest({{0, 1, 0}, {1, 0, 0}, 0.f, kInf}, floor).id, kNoHit);
  EXPECT_EQ(closest({{0, 0, 0}, {1, 0, 0}, 0.f, kInf}, floor).id, kNoHit);
}

TEST(PlaneKernel, RespectsOpenInterval) {
  const PlaneSoA floor = planes_of({{{0, 0, 0}, {0, 1, 0}}});
  EXPECT_EQ(closest({{0, 1, 0}, {0, -1, 0}, 0.f, 1.f}, floor).id, kNoHit);   // t == tmax
  EXPECT_EQ(closest({{0, 1, 0}, {0, -1, 0}, 1.f, 5.f}, floor).id, kNoHit);   // t == tmin
  EXPECT_EQ(closest({{0, 1, 0}, {0, 1, 0}, 0.f, kInf}, floor).id, kNoHit);   // behind
  EXPECT_EQ(closest({{0, 0, 0}, {0, -1, 0}, 0.f, kInf}, floor).id, kNoHit);  // origin on plane, t = 0
}

TEST(PlaneKernel, ClosestOfSeveralAndTieGoesToFirst) {
  const PlaneSoA planes = planes_of({{{0, 0, 0}, {0, 1, 0}}, {{0, 2, 0}, {0, 1, 0}}, {{0, 2, 0}, {0, -1, 0}}});
  const Hit<float> h = closest({{0, 5, 0}, {0, -1, 0}, 0.f, kInf}, planes);
  EXPECT_EQ(h.id, 1);
  EXPECT_FLOAT_EQ(h.t, 3.f);
}

TEST(PlaneBuild, DropsDegenerateAndNonFinite) {
  BuildReport report;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const PlaneSoA soa = planes_of({{{0, 0, 0}, {0, 0, 0}},
                                  {{nan, 0, 0}, {0, 1, 0}},
                                  {{0, 0, 0}, {0, kInf, 0}},
                                  {{0, 0, 0}, {1e-30f, 0, 0}},
                                  {{0, 1, 0}, {0, 3, 0}}},
                                 &report);
  EXPECT_EQ(soa.size(), 1u);
  EXPECT_EQ(report.kept, 1u);
  EXPECT_EQ(report.dropped_non_finite, 2u);
  EXPECT_EQ(report.dropped_degenerate, 2u);  // zero normal; 1e-30 whose squared length underflows
  EXPECT_FLOAT_EQ(soa.ny[0], 1.f);           // normalised
  EXPECT_FLOAT_EQ(soa.d[0], -1.f);
  for (float v : soa.nx) EXPECT_TRUE(std::isfinite(v));
}

template <class W>
class PlaneWidths : public testing::UnitTest<W> {};
TYPED_TEST_SUITE(PlaneWidths, testing::KernelUnits);

PlaneSoA random_planes(RaySampler& s, std::size_t n) {
  std::vector<PlaneDesc> descs;
  for (std::size_t i = 0; i < n; ++i) descs.push_back({s.in_box({-5, -5, -5}, {5, 5, 5}), s.unit_direction()});
  BuildReport report;
  return build_planes(descs, report);
}

TYPED_TEST(PlaneWidths, MatchesScalarBitForBit) {
  RaySampler s(7);
  const PlaneSoA planes = random_planes(s, 13);  // not a multiple of any width
  std::vector<Ray<float>> rays = testing::adversarial_rays(s, 50'003, {0, 0, 0}, 5.f);
  for (int i = 0; i < 50'000; ++i) rays.push_back(s.toward(s.in_box({-9, -9, -9}, {9, 9, 9}), s.in_box({-5, -5, -5}, {5, 5, 5})));
  for (int i = 0; i < 1'000; ++i) {  // grazing: nearly parallel to plane 0
    const Vec3<float> n{planes.nx[0], planes.ny[0], planes.nz[0]};
    const Vec3<float> d = cross(n, s.unit_direction());
    rays.push_back({s.in_box({-5, -5, -5}, {5, 5, 5}), d + n * s.uniform(-1e-6f, 1e-6f), 0.f, kInf});
  }
  RaySoA soa = testing::to_soa(rays);
  testing::poison_padding(soa);
  const auto ref = testing::expect_streams_match_scalar(plane_streams<KernelUnit::scalar>(PlaneMethod::seed),
                                                        plane_streams<TestFixture::kUnit>(PlaneMethod::seed), soa, planes);
  EXPECT_GT(ref.closest_packets.hit_count(), rays.size() / 2);  // the test exercises hits
}

// Streams compose: a ray a previous store already occluded stays occluded,
// in every unit, even when this store cannot block it.
TYPED_TEST(PlaneWidths, OccludedStreamsKeepEarlierOcclusion) {
  PlaneDesc floor{{0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}};
  BuildReport report;
  const PlaneSoA planes = build_planes(std::span(&floor, 1), report);
  std::vector<Ray<float>> rays;
  for (int i = 0; i < 19; ++i) rays.push_back({{float(i), 1.f, 0.f}, {0.f, 1.f, 0.f}, 0.f, kInf});  // away: miss
  const RaySoA soa = testing::to_soa(rays);
  OcclusionSoA result(soa);
  for (std::size_t i = 0; i < rays.size(); i += 3) result.occluded[i] = 1;
  plane_streams<TestFixture::kUnit>(PlaneMethod::seed).occluded_packets(soa, planes, result);
  for (std::size_t i = 0; i < rays.size(); ++i) EXPECT_EQ(result.occluded[i], i % 3 == 0 ? 1 : 0) << "ray " << i;
}

}  // namespace
}  // namespace quiver
