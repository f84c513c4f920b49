// The lane-generic power (simd/power.h) against libm in double: relative
// error within its stated bound over the shininess range scenes use, exact
// at the edges the shading relies on. (Every width runs the same formula; the
// whole-image test RenderUnits.GiveTheScalarReferenceBits checks their bits.)
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "simd/power.h"

namespace quiver {
namespace {

// The error is the float log2's, scaled by the exponent: 2 |s log2 x| + 4 ulps.
TEST(Power, WithinTheStatedBoundOfLibmOverTheSpecularRange) {
  const float epsilon = std::numeric_limits<float>::epsilon();
  double worst = 0.0;
  for (float s : {0.5f, 1.f, 2.f, 7.5f, 32.f, 100.f, 1000.f, 10000.f}) {
    for (int i = 1; i <= 4000; ++i) {
      const float x = float(i) / 4000.f;
      const double exact = std::pow(double(x), double(s));
      if (exact < 1e-36) continue;  // flushed below 2^-126 by contract
      const double relative = std::fabs(double(pow_lanes(x, s)) - exact) / exact;
      worst = std::max(worst, relative);
      const double y = std::fabs(double(s) * std::log2(double(x)));
      ASSERT_LE(relative, (2.0 * y + 4.0) * epsilon) << "x = " << x << ", s = " << s;
    }
  }
  EXPECT_GT(worst, 0.0);  // the polynomials are approximations: some error shows
}

TEST(Power, ExactAtOneAndAtExponentZero) {
  for (float s : {0.f, 1.f, 32.f, 1e4f}) EXPECT_EQ(pow_lanes(1.f, s), 1.f) << s;
  for (float x : {1e-30f, 0.25f, 0.999f}) EXPECT_EQ(pow_lanes(x, 0.f), 1.f) << x;
  EXPECT_EQ(pow_lanes(0.5f, 1.f), 0.5f);
  EXPECT_EQ(pow_lanes(0.5f, 3.f), 0.125f);
}

TEST(Power, UnderflowGivesZeroNotGarbage) {
  EXPECT_EQ(pow_lanes(0.5f, 200.f), 0.f);
  EXPECT_EQ(pow_lanes(std::numeric_limits<float>::denorm_min(), 2.f), 0.f);
  EXPECT_EQ(pow_lanes(1e-20f, 10.f), 0.f);
}

}  // namespace
}  // namespace quiver
