#include <bit>
#include <cmath>
#include <cstdlib>
#include <limits>

#include <gtest/gtest.h>

#include "simd/isa.h"
#include "simd/lanes.h"
#include "simd/vec3.h"
#include "tests/support/kernel_checks.h"
#include "tests/support/left_pack_units.h"

namespace quiver {
namespace {

TEST(Lanes, MinMaxSelectNaNAndSignedZeroRule) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  // min(a, b) = b < a ? b : a: a NaN in b keeps a, a NaN in a stays.
  EXPECT_EQ(min(1.f, nan), 1.f);
  EXPECT_TRUE(std::isnan(min(nan, 1.f)));
  EXPECT_TRUE(std::signbit(min(-0.f, 0.f)));
  EXPECT_FALSE(std::signbit(min(0.f, -0.f)));
  EXPECT_EQ(max(2.f, 3.f), 3.f);
}

TEST(Lanes, ScalarFmaIsFused) {
  // (1 + 2^-23)(1 - 2^-23) - 1 = -2^-46 exactly; unfused it rounds to 0.
  const float a = 1.f + std::ldexp(1.f, -23), b = 1.f - std::ldexp(1.f, -23);
  EXPECT_EQ(fma(a, b, -1.f), -std::ldexp(1.f, -46));
}

TEST(Lanes, DifferenceOfProductsBeatsNaiveCancellation) {
  // a*b - c*d with a*b == c*d after rounding but not exactly.
  const float a = 1.f + std::ldexp(1.f, -12), b = 1.f + std::ldexp(1.f, -12);
  const float c = 1.f + std::ldexp(1.f, -11), d = 1.f;
  const double exact = double(a) * b - double(c) * d;  // 2^-24
  EXPECT_EQ(difference_of_products(a, b, c, d), float(exact));
  EXPECT_NE(a * b - c * d, float(exact));
}

TEST(Lanes, CrossAccurateIsPerpendicular) {
  const Vec3<float> a{1e4f, 1.f + 1e-4f, 3.f}, b{1e4f, 1.f, 3.f - 1e-4f};
  const Vec3<float> c = cross_accurate(a, b);
  const Vec3<double> ad{a.x, a.y, a.z}, bd{b.x, b.y, b.z};
  const Vec3<double> cd{ad.y * bd.z - ad.z * bd.y, ad.z * bd.x - ad.x * bd.z, ad.x * bd.y - ad.y * bd.x};
  EXPECT_NEAR(c.x, cd.x, std::abs(cd.x) * 2e-7);
  EXPECT_NEAR(c.y, cd.y, std::abs(cd.y) * 2e-7);
  EXPECT_NEAR(c.z, cd.z, std::abs(cd.z) * 2e-7);
}

// The lanes' a < b (the closest-hit tie rule's id order) is the scalar
// reference's, equal ids included, over the whole id range.
TEST(Lanes, IntLessOfLanesIsTheScalarLessThan) {
  using Ints = xsimd::batch<std::int32_t>;
  constexpr std::size_t kWidth = Ints::size;
  const std::int32_t ids[] = {-1, 0, 1, 2, (1 << 24) + 1, (1 << 24) + 2, std::numeric_limits<std::int32_t>::max() - 1};
  for (std::int32_t a : ids) {
    for (std::int32_t b : ids) {
      const auto mask = int_less(Ints(a), Ints(b));
      for (std::size_t lane = 0; lane < kWidth; ++lane) {
        EXPECT_EQ(bool(mask.get(lane)), int_less(a, b)) << a << " < " << b << " in lane " << lane;
      }
    }
  }
}

// The lanes' finiteness test is std::isfinite's at the edges of the range:
// the largest finite float is finite, infinities and NaN are not.
TEST(Lanes, FiniteLanesAreStdIsfiniteAtTheRangesEdges) {
  using Floats = xsimd::batch<float>;
  constexpr float kMax = std::numeric_limits<float>::max(), kInf = std::numeric_limits<float>::infinity();
  const float values[] = {0.f, -0.f, std::numeric_limits<float>::denorm_min(), 1.f, std::nextafter(kMax, 0.f), kMax,
                          -kMax, kInf, -kInf, std::numeric_limits<float>::quiet_NaN()};
  for (float v : values) {
    const auto mask = isfinite_lanes(Floats(v));
    for (std::size_t lane = 0; lane < Floats::size; ++lane) {
      EXPECT_EQ(bool(mask.get(lane)), bool(std::isfinite(v))) << v << " in lane " << lane;
    }
    EXPECT_EQ(isfinite_lanes(v), bool(std::isfinite(v))) << v;
  }
}

TEST(Lanes, MasksDifferIsXorAtWidth1) {
  EXPECT_FALSE(masks_differ(true, true));
  EXPECT_TRUE(masks_differ(true, false));
  EXPECT_FALSE(masks_differ(false, false));
}

// Left-packing stores at every width: each mask's set lanes land in order,
// nothing past them is written (the shadow-ray appends rely on both).
template <class U>
class LeftPack : public testing::UnitTest<U> {};
TYPED_TEST_SUITE(LeftPack, testing::KernelUnits);

TYPED_TEST(LeftPack, EveryMaskStoresItsSetLanesInOrderAndNothingElse) {
  EXPECT_EQ(testing::left_pack_every_mask<TestFixture::kUnit>(), "");
}

TEST(Isa, ResolveNamesAndRejectsUnknown) {
  EXPECT_EQ(resolve_isa("scalar"), Isa::scalar);
  EXPECT_EQ(resolve_isa("auto"), best_supported_isa());
  EXPECT_EQ(resolve_isa(""), best_supported_isa());
  EXPECT_THROW(resolve_isa("avx1024"), std::runtime_error);
  EXPECT_EQ(lane_width(Isa::avx512), 16);
  EXPECT_EQ(kernel_unit_for(Isa::avx512), KernelUnit::avx512);
  EXPECT_EQ(lane_width(Isa::sse4), 4);
  EXPECT_EQ(lane_width(Isa::avx2), 8);
  EXPECT_EQ(kernel_unit_for(Isa::avx2), KernelUnit::avx2);
  EXPECT_EQ(lane_width(KernelUnit::scalar_fma), 1);
  EXPECT_EQ(kernel_unit_for(Isa::scalar),
            kernel_unit_supported(KernelUnit::scalar_fma) ? KernelUnit::scalar_fma : KernelUnit::scalar);
  EXPECT_TRUE(isa_supported(Isa::scalar));
}

// auto is the widest choice this CPU runs.
TEST(Isa, TheBestSupportedIsTheWidest) {
  const Isa best = best_supported_isa();
  EXPECT_TRUE(isa_supported(best));
  for (const Isa isa : kIsas) {
    if (isa_supported(isa)) {
      EXPECT_GE(lane_width(best), lane_width(isa)) << isa_name(isa);
    }
  }
}

TEST(Isa, EveryUnitRunsAChoiceOfItsWidth) {
  for (KernelUnit unit : kKernelUnits) {
    EXPECT_EQ(lane_width(isa_of(unit)), lane_width(unit)) << kernel_unit_name(unit);
    EXPECT_EQ(lane_width(kernel_unit_for(isa_of(unit))), lane_width(unit)) << kernel_unit_name(unit);
  }
}

TEST(Isa, EnvironmentForcesChoice) {
  ::setenv("QUIVER_SIMD", "scalar", 1);
  EXPECT_EQ(isa_from_environment(), Isa::scalar);
  ::setenv("QUIVER_SIMD", "nonsense", 1);
  EXPECT_THROW(isa_from_environment(), std::runtime_error);
  ::unsetenv("QUIVER_SIMD");
  EXPECT_EQ(isa_from_environment(), best_supported_isa());
}

}  // namespace
}  // namespace quiver
