// x^s for x in (0, 1] and s >= 0, the Phong specular power, one formula for
// every width (so the scalar reference and the packets agree bit for bit;
// libm's powf has no lane form):
//   log2 x = e + log2 m from the float's bits, m in [sqrt(1/2), sqrt(2)),
//     ln m = 2 atanh(f) = 2 (f + f^3/3 + ... + f^9/9), f = (m - 1) / (m + 1),
//     |f| <= 0.172, so the first term left out is below 2^-31 (Cody and
//     Waite, "Software Manual for the Elementary Functions", ch. 5);
//   2^y = 2^n e^(r ln 2), n = floor(y + 1/2), |r ln 2| <= 0.347, Taylor to
//     degree 7 (the next term is below 2^-30), 2^n built from its bits.
// Relative error at most (2 |s log2 x| + 4) ulps (the float log2's rounding,
// scaled by s; tests/simd_power_test.cpp), so below 2^-16 for any result
// above 2^-126; smaller results (y < -126.5) are 0. Lanes with x <= 0 or NaN give garbage
// that callers mask off; x below the smallest normal counts as it.
#pragma once

#include <cstdint>
#include <limits>

#include "simd/lanes.h"

namespace quiver {

inline namespace QUIVER_UNIT_NAMESPACE {

template <class F>
inline F to_float_lanes(const IntLanes<F>& i) {
  if constexpr (lane_count<F> == 1) {
    return static_cast<float>(i);
  } else {
    return xsimd::to_float(i);
  }
}

template <class F>
inline F floor_lanes(const F& x) {
  if constexpr (lane_count<F> == 1) {
    return std::floor(x);
  } else {
    return xsimd::floor(x);
  }
}

// An integer-valued float in [-2^31, 2^31) as int lanes.
template <class F>
inline IntLanes<F> to_int_lanes(const F& x) {
  if constexpr (lane_count<F> == 1) {
    return static_cast<std::int32_t>(x);
  } else {
    return xsimd::to_int(x);
  }
}

template <class F>
inline F log2_lanes(const F& x_in) {
  using Int = IntLanes<F>;
  const F x = max(x_in, F(std::numeric_limits<float>::min()));
  const Int bits = float_bits(x);
  // x = 2^e m, m in [1, 2), then folded into [sqrt(1/2), sqrt(2)).
  const Int biased = bits >> 23;
  const F m1 = float_of_bits((bits & Int(0x007fffff)) | Int(0x3f800000));
  const Mask<F> high = m1 > F(1.41421356f);
  const F m = select(high, m1 * F(0.5f), m1);
  const F e = to_float_lanes<F>(biased - Int(127)) + select(high, F(1.f), F(0.f));
  // ln m = 2 f (1 + f^2/3 + f^4/5 + f^6/7 + f^8/9).
  const F f = (m - F(1.f)) / (m + F(1.f));
  const F f2 = f * f;
  F series = fma(f2, F(1.f / 9.f), F(1.f / 7.f));
  series = fma(f2, series, F(1.f / 5.f));
  series = fma(f2, series, F(1.f / 3.f));
  series = fma(f2, series, F(1.f));
  const F ln_m = F(2.f) * f * series;
  return fma(ln_m, F(1.44269504f), e);  // log2 m = ln m / ln 2
}

// 2^y for y <= 0 (larger y is not needed here and is not handled).
template <class F>
inline F exp2_lanes(const F& y_in) {
  using Int = IntLanes<F>;
  const F y = max(y_in, F(-127.f));
  const F n = floor_lanes(y + F(0.5f));
  const F z = (y - n) * F(0.693147181f);  // r ln 2
  // e^z by Horner: 1 + z (1 + z (1/2 + z (1/6 + ... + z / 7!))).
  F p = fma(z, F(1.f / 5040.f), F(1.f / 720.f));
  p = fma(z, p, F(1.f / 120.f));
  p = fma(z, p, F(1.f / 24.f));
  p = fma(z, p, F(1.f / 6.f));
  p = fma(z, p, F(0.5f));
  p = fma(z, p, F(1.f));
  p = fma(z, p, F(1.f));
  // 2^n from its exponent bits; n = -127 gives the bits of +0.
  const F scale = float_of_bits((to_int_lanes(n) + Int(127)) << 23);
  return p * scale;
}

template <class F>
inline F pow_lanes(const F& x, const F& s) {
  return exp2_lanes(s * log2_lanes(x));
}

}  // namespace QUIVER_UNIT_NAMESPACE
}  // namespace quiver
