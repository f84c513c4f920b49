// Hit footprints in lanes (integrator/hit_footprints.h): every kernel unit
// gives, for each ray of a wave that hit, transfer_differential's bits in
// one lane, and 0 for a miss, a last partial packet included.
#include <bit>
#include <cstdint>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "integrator/hit_footprints.h"
#include "integrator/ray_differentials.h"

namespace quiver {
namespace {

class HitFootprintsUnits : public ::testing::TestWithParam<KernelUnit> {};

std::uint32_t bits(float v) { return std::bit_cast<std::uint32_t>(v); }

TEST_P(HitFootprintsUnits, CarryEachHitsDifferentialsAsOneLaneDoes) {
  const KernelUnit unit = GetParam();
  if (!kernel_unit_supported(unit)) GTEST_SKIP() << "this CPU cannot run " << kernel_unit_name(unit);
  std::mt19937 random(11);
  std::uniform_real_distribution<float> value(-2.f, 2.f);
  const auto vector = [&] { return Vec3<float>{value(random), value(random), value(random)}; };
  RaySoA rays;
  DifferentialColumns differentials;
  const std::size_t count = 37;  // no width divides it
  for (std::size_t i = 0; i < count; ++i) {
    rays.push(Ray<float>{vector(), vector(), 0.f, 100.f});
    for (Vec3Columns* c : differentials.vectors()) c->push(vector() * 0.01f);
    differentials.centre_x.push_back(0.f);
    differentials.centre_y.push_back(0.f);
  }
  rays.pad();
  differentials.pad(count);
  HitSoA hits(rays);
  for (std::size_t i = 0; i < count; ++i) {
    if (i % 4 == 3) continue;  // a miss
    hits.set(i, Hit<float>{1.f + float(i) * 0.1f, 0.2f, 0.3f, vector(), std::int32_t(i)});
  }
  Vec3Columns point_dx, point_dy;
  for (Vec3Columns* c : {&point_dx, &point_dy}) {
    for (AlignedFloats* column : c->columns()) column->assign(rays.ox.size(), 5.f);
  }
  with_kernel_unit(unit, [&](auto u) {
    hit_footprints<decltype(u)::value>(rays, hits, differentials, point_dx, point_dy);
  });
  std::size_t met = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const Ray<float> ray = rays.get(i);
    const Hit<float> hit = hits.get(i);
    Vec3<float> dx{0.f, 0.f, 0.f}, dy{0.f, 0.f, 0.f};
    if (hit.id != kNoHit) {
      ++met;
      dx = transfer_differential(differentials.origin_dx.get(i), differentials.direction_dx.get(i), ray.direction,
                                 hit.t, hit.ng);
      dy = transfer_differential(differentials.origin_dy.get(i), differentials.direction_dy.get(i), ray.direction,
                                 hit.t, hit.ng);
    }
    const std::string where = std::string(kernel_unit_name(unit)) + " ray " + std::to_string(i);
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_EQ(bits(point_dx.get(i)[axis]), bits(dx[axis])) << where << " axis " << axis;
      EXPECT_EQ(bits(point_dy.get(i)[axis]), bits(dy[axis])) << where << " axis " << axis;
    }
  }
  EXPECT_EQ(met, count - count / 4);
}

INSTANTIATE_TEST_SUITE_P(EveryUnit, HitFootprintsUnits, ::testing::ValuesIn(kKernelUnits),
                         [](const ::testing::TestParamInfo<KernelUnit>& info) {
                           return std::string(kernel_unit_name(info.param));
                         });

}  // namespace
}  // namespace quiver
