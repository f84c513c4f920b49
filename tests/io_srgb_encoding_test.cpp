// The sRGB byte lookup against the formula it stands for: every float near
// each code's step (where a lookup could be off by one), special values,
// a sweep over [0, 1], and the conversion of many values at once.
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "io/srgb_encoding.h"

namespace quiver {
namespace {

TEST(SrgbEncoding, LookupMatchesTheFormulaAroundEveryStep) {
  for (int k = 1; k <= 255; ++k) {
    // The linear value whose encoding is k - 0.5 of 255 (the step to code k).
    const double encoded = (k - 0.5) / 255.0;
    const double step = encoded <= 12.92 * 0.0031308 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
    const std::int64_t centre = std::bit_cast<std::int32_t>(float(step));
    int below = 0, above = 0;
    for (std::int64_t bits = centre - 4096; bits <= centre + 4096; ++bits) {
      const float linear = std::bit_cast<float>(std::int32_t(bits));
      const int expected = srgb_byte_formula(linear);
      ASSERT_EQ(int(srgb_byte(linear)), expected) << "code " << k << ", linear " << linear;
      below += expected == k - 1;
      above += expected == k;
    }
    EXPECT_GT(below, 0) << k;  // the window spans the step
    EXPECT_GT(above, 0) << k;
  }
}

TEST(SrgbEncoding, SpecialValuesAndASweepOfTheUnitInterval) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  for (const float v : {nan, -nan, inf, -inf, 0.f, -0.f, -1e-30f, -0.5f, std::numeric_limits<float>::denorm_min(),
                        std::numeric_limits<float>::min(), 0.0031308f, 0.5f, std::nextafter(1.f, 0.f), 1.f, 1.5f,
                        std::numeric_limits<float>::max()}) {
    EXPECT_EQ(int(srgb_byte(v)), int(srgb_byte_formula(v))) << v;
  }
  EXPECT_EQ(srgb_byte(nan), 0);
  EXPECT_EQ(srgb_byte(-0.5f), 0);
  EXPECT_EQ(srgb_byte(0.5f), 188);
  EXPECT_EQ(srgb_byte(inf), 255);
  for (int i = 0; i <= 1'000'000; ++i) {
    const float linear = float(i) / 1e6f;
    ASSERT_EQ(int(srgb_byte(linear)), int(srgb_byte_formula(linear))) << linear;
  }
}

TEST(SrgbEncoding, ManyAtOnceAsOneAtATime) {
  std::vector<float> linear;
  for (int i = -10; i <= 1010; ++i) linear.push_back(float(i) / 1000.f);
  linear.push_back(std::numeric_limits<float>::quiet_NaN());
  std::vector<std::uint8_t> codes(linear.size(), 7);
  srgb_bytes(linear, codes);
  for (std::size_t i = 0; i < linear.size(); ++i) EXPECT_EQ(codes[i], srgb_byte(linear[i])) << linear[i];
  EXPECT_EQ(codes.front(), 0);
  EXPECT_EQ(codes[1010], 255);
}

}  // namespace
}  // namespace quiver
