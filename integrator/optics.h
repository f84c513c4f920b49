// Ray directions at a surface and safe origins for the rays leaving it.
//   reflect: R = I - 2 (I.N) N (Whitted 1980).
//   refract: Snell's law in the seed's vector form: with eta = n1 / n2,
//     c1 = -I.N and k = 1 - eta^2 (1 - c1^2), T = eta I + (eta c1 - sqrt k) N;
//     k < 0 is total internal reflection (no T, never a NaN).
//   offset_origin: the hit point moved off the surface by a bound on its own
//     rounding error, along the side's normal, then one more ulp outward per
//     component (after pbrt-v4's OffsetRayOrigin). The bound scales with the
//     magnitudes that produced the point, so no scene-dependent epsilon.
// I and N are unit vectors, N on the side I comes from (I.N <= 0).
#pragma once

#include <cmath>
#include <limits>
#include <optional>

#include "simd/lanes.h"

namespace quiver {

inline namespace QUIVER_UNIT_NAMESPACE {

inline Vec3<float> reflect(const Vec3<float>& incident, const Vec3<float>& normal) {
  const float two_cos = 2.f * dot(incident, normal);
  return incident - normal * two_cos;
}

inline std::optional<Vec3<float>> refract(const Vec3<float>& incident, const Vec3<float>& normal, float eta) {
  const float c1 = -dot(incident, normal);
  const float k = 1.f - eta * eta * (1.f - c1 * c1);
  if (k < 0.f) return std::nullopt;  // total internal reflection
  return incident * eta + normal * (eta * c1 - std::sqrt(k));
}

// Rounding error of p = o + t d per component, from |o| and |t d|: a few
// ulps for the sum and product plus the kernels' error in t. With 0 the
// acne test (tests/integrator_render_test.cpp) fails at every scale; 64 is
// a margin, still ~4e-6 of the magnitudes involved.
inline constexpr float kOffsetErrorUlps = 64.f;

inline Vec3<float> hit_point_error(const Vec3<float>& origin, const Vec3<float>& direction, float t) {
  const float e = kOffsetErrorUlps * std::numeric_limits<float>::epsilon();
  return {e * (std::fabs(origin.x) + std::fabs(t * direction.x)),
          e * (std::fabs(origin.y) + std::fabs(t * direction.y)),
          e * (std::fabs(origin.z) + std::fabs(t * direction.z))};
}

// p moved to the side `side_normal` (unit) points to, clear of its error.
inline Vec3<float> offset_origin(const Vec3<float>& p, const Vec3<float>& error, const Vec3<float>& side_normal) {
  const float distance = std::fabs(side_normal.x) * error.x + std::fabs(side_normal.y) * error.y +
                         std::fabs(side_normal.z) * error.z;
  Vec3<float> moved = p + side_normal * distance;
  for (int a = 0; a < 3; ++a) {
    const float away = side_normal[a] > 0.f ? std::numeric_limits<float>::infinity()
                                            : -std::numeric_limits<float>::infinity();
    if (side_normal[a] != 0.f) moved[a] = std::nextafter(moved[a], away);
  }
  return moved;
}

}  // namespace QUIVER_UNIT_NAMESPACE
}  // namespace quiver
