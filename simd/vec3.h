// Vec3<F>: three lanes of F (a point or direction per lane), or three plain
// numbers (float, double). Plain arithmetic evaluated left to right;
// contraction is off, so a product-sum rounds the same at every width. fma
// appears only where written. No xsimd here: the forms that need lane
// operations (select, length, normalize, ...) are in simd/lanes.h.
#pragma once

#include <cmath>
#include <type_traits>

#include "simd/kernel_units.h"

namespace quiver {

template <class F>
struct Vec3 {
  F x, y, z;

  Vec3() = default;
  Vec3(const F& x_, const F& y_, const F& z_) : x(x_), y(y_), z(z_) {}
  // Broadcast a scalar vector to every lane.
  template <class G = F, class = std::enable_if_t<!std::is_same_v<G, float>>>
  explicit Vec3(const Vec3<float>& s) : x(s.x), y(s.y), z(s.z) {}

  F& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
  const F& operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
};

inline namespace QUIVER_UNIT_NAMESPACE {

template <class F>
inline Vec3<F> operator+(const Vec3<F>& a, const Vec3<F>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class F>
inline Vec3<F> operator-(const Vec3<F>& a, const Vec3<F>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class F>
inline Vec3<F> operator-(const Vec3<F>& a) {
  return {-a.x, -a.y, -a.z};
}
template <class F>
inline Vec3<F> operator*(const Vec3<F>& a, const F& s) {
  return {a.x * s, a.y * s, a.z * s};
}
template <class F>
inline Vec3<F> operator*(const F& s, const Vec3<F>& a) {
  return {s * a.x, s * a.y, s * a.z};
}
template <class F>
inline Vec3<F> operator/(const Vec3<F>& a, const F& s) {
  return {a.x / s, a.y / s, a.z / s};
}

template <class F>
inline F dot(const Vec3<F>& a, const Vec3<F>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class F>
inline Vec3<F> cross(const Vec3<F>& a, const Vec3<F>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
// Every component finite (plain numbers: float, double).
template <class F, class = std::enable_if_t<std::is_floating_point_v<F>>>
inline bool all_finite(const Vec3<F>& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace QUIVER_UNIT_NAMESPACE
}  // namespace quiver
