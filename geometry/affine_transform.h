// An affine map p -> A p + b as a 3x4 matrix, row-major (row r: A's row r,
// then b[r]), applied with one formula for every width: points, vectors
// (A only) and normals (the transpose of the inverse's A, so an instance's
// normals come from its world-to-object matrix). Each row is evaluated left
// to right, products then sums, no fma: every width rounds alike.
#pragma once

#include <array>
#include <optional>

#include "simd/vec3.h"

namespace quiver {

struct AffineTransform {
  std::array<float, 12> m{1.f, 0.f, 0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 0.f, 1.f, 0.f};

  float at(int row, int column) const { return m[static_cast<std::size_t>(4 * row + column)]; }
};

// The inverse, computed in double and rounded once; nullopt when the
// matrix is singular or the inverse is not finite in float.
std::optional<AffineTransform> inverse(const AffineTransform& t);

// |A| and |b| entry by entry: bounds how the map scales rounding errors.
AffineTransform absolute(const AffineTransform& t);

inline namespace QUIVER_UNIT_NAMESPACE {

template <class F>
inline F row_times(const AffineTransform& t, int row, const Vec3<F>& v) {
  return F(t.at(row, 0)) * v.x + F(t.at(row, 1)) * v.y + F(t.at(row, 2)) * v.z;
}

template <class F>
inline Vec3<F> apply_vector(const AffineTransform& t, const Vec3<F>& v) {
  return {row_times(t, 0, v), row_times(t, 1, v), row_times(t, 2, v)};
}

template <class F>
inline Vec3<F> apply_point(const AffineTransform& t, const Vec3<F>& p) {
  return {row_times(t, 0, p) + F(t.at(0, 3)), row_times(t, 1, p) + F(t.at(1, 3)), row_times(t, 2, p) + F(t.at(2, 3))};
}

// n by the transpose of `inverse`'s A: a normal of the map whose inverse
// that is (not unit length).
template <class F>
inline Vec3<F> apply_normal(const AffineTransform& inverse, const Vec3<F>& n) {
  return {F(inverse.at(0, 0)) * n.x + F(inverse.at(1, 0)) * n.y + F(inverse.at(2, 0)) * n.z,
          F(inverse.at(0, 1)) * n.x + F(inverse.at(1, 1)) * n.y + F(inverse.at(2, 1)) * n.z,
          F(inverse.at(0, 2)) * n.x + F(inverse.at(1, 2)) * n.y + F(inverse.at(2, 2)) * n.z};
}

}  // namespace QUIVER_UNIT_NAMESPACE
}  // namespace quiver
