// Lane64: one double as a kernel lane, so every kernel template in
// geometry/*.h can be evaluated at double precision with exactly its float
// formula (the "double" point of the accuracy charts).
// Why a wrapper and not plain double: simd/lanes.h defines the lane traits and
// the scalar select / fma / sqrt / abs / isfinite_lanes for float only, so
// Ray<double> does not compile, and a plain double would silently bind to
// the float overloads (double -> float converts implicitly). Lane64 converts
// to nothing, its operations live in this namespace (found by argument-
// dependent lookup when the kernel templates are instantiated), and every
// operation is one IEEE double operation (std::fma rounds once).
#pragma once

#include <cmath>
#include <cstdint>

#include "simd/lanes.h"

namespace quiver::accuracy {

struct Lane64 {
  double value = 0.0;

  Lane64() = default;
  explicit Lane64(double v) : value(v) {}
  explicit Lane64(float v) : value(v) {}
};

inline Lane64 operator+(Lane64 a, Lane64 b) { return Lane64(a.value + b.value); }
inline Lane64 operator-(Lane64 a, Lane64 b) { return Lane64(a.value - b.value); }
inline Lane64 operator*(Lane64 a, Lane64 b) { return Lane64(a.value * b.value); }
inline Lane64 operator/(Lane64 a, Lane64 b) { return Lane64(a.value / b.value); }
inline Lane64 operator-(Lane64 a) { return Lane64(-a.value); }
inline bool operator<(Lane64 a, Lane64 b) { return a.value < b.value; }
inline bool operator>(Lane64 a, Lane64 b) { return a.value > b.value; }
inline bool operator<=(Lane64 a, Lane64 b) { return a.value <= b.value; }
inline bool operator>=(Lane64 a, Lane64 b) { return a.value >= b.value; }
inline bool operator==(Lane64 a, Lane64 b) { return a.value == b.value; }
inline bool operator!=(Lane64 a, Lane64 b) { return a.value != b.value; }

inline Lane64 select(bool m, Lane64 a, Lane64 b) { return m ? a : b; }
inline Lane64 fma(Lane64 a, Lane64 b, Lane64 c) { return Lane64(std::fma(a.value, b.value, c.value)); }
inline Lane64 sqrt(Lane64 a) { return Lane64(std::sqrt(a.value)); }
inline Lane64 abs(Lane64 a) { return Lane64(std::fabs(a.value)); }
inline bool isfinite_lanes(Lane64 a) { return std::isfinite(a.value); }
// Rounded to float: the polygon kernel picks an edge band from it, and
// rounding is monotonic, so the band still holds every edge the double v
// straddles (geometry/kinds/polygon.h).
inline void store_lanes(Lane64 v, float* p) { *p = static_cast<float>(v.value); }

}  // namespace quiver::accuracy

namespace quiver {

template <>
struct LaneTraits<accuracy::Lane64> {
  using Mask = bool;
  using Int = std::int32_t;
  static constexpr int width = 1;
};

}  // namespace quiver
