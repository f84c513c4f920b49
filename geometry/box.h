// Axis-aligned boxes for the BVH build: the empty box is inverted
// (lo = +inf, hi = -inf), so growing it by anything gives that thing.
#pragma once

#include <algorithm>
#include <limits>

#include "simd/vec3.h"

namespace quiver {

struct Box {
  Vec3<float> lo, hi;
};

inline namespace QUIVER_UNIT_NAMESPACE {

inline Box empty_box() {
  constexpr float inf = std::numeric_limits<float>::infinity();
  return {{inf, inf, inf}, {-inf, -inf, -inf}};
}

inline void grow(Box& b, const Vec3<float>& p) {
  for (int a = 0; a < 3; ++a) {
    b.lo[a] = std::min(b.lo[a], p[a]);
    b.hi[a] = std::max(b.hi[a], p[a]);
  }
}

// The union: lo with lo, hi with hi, so an empty `other` leaves b as it is
// (growing by its corners would take its +inf hi and -inf lo).
inline void grow(Box& b, const Box& other) {
  for (int a = 0; a < 3; ++a) {
    b.lo[a] = std::min(b.lo[a], other.lo[a]);
    b.hi[a] = std::max(b.hi[a], other.hi[a]);
  }
}

inline bool is_empty(const Box& b) { return !(b.lo.x <= b.hi.x); }

// Half the surface area of a box of extent e (the SAH compares only ratios).
inline float half_area_of_extent(const Vec3<float>& e) { return e.x * e.y + e.y * e.z + e.z * e.x; }

// Half the surface area; 0 for an empty box.
inline float half_area(const Box& b) { return is_empty(b) ? 0.f : half_area_of_extent(b.hi - b.lo); }

// (lo + hi) / 2 per coordinate, for a Vec3 or for lanes of coordinates.
template <class T>
inline T midpoint_of(const T& lo, const T& hi) {
  return (lo + hi) * 0.5f;
}

inline Vec3<float> centroid(const Box& b) { return midpoint_of(b.lo, b.hi); }

}  // namespace QUIVER_UNIT_NAMESPACE
}  // namespace quiver
