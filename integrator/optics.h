// Ray directions at a surface and safe origins for the rays leaving it, one
// formula for every width (F = float, the reference, or a batch):
//   reflect: R = I - 2 (I.N) N (Whitted 1980).
//   refract: Snell's law in the seed's vector form: with eta = n1 / n2,
//     c1 = -I.N and k = 1 - eta^2 (1 - c1^2), T = eta I + (eta c1 - sqrt k) N;
//     k < 0 is total internal reflection: the lane's mask is off and its T
//     is finite garbage (sqrt of 0), never a NaN.
//   offset_origin: the hit point moved off the surface by a bound on its own
//     rounding error, along the side's normal, then one more ulp outward per
//     component (after pbrt-v4's OffsetRayOrigin). The bound scales with the
//     magnitudes that produced the point, so no scene-dependent epsilon.
//   fresnel_reflectance: a dielectric's reflectance for unpolarised light,
//     F = (rs^2 + rp^2) / 2 with rs = (eta c1 - c2) / (eta c1 + c2) and
//     rp = (c1 - eta c2) / (c1 + eta c2), c1 = -I.N, c2 = sqrt k (refract's
//     k); 1 where k < 0 (total internal reflection).
//   terminator_lift_share: how much of that lift a shadow ray takes, by N.L
//     and Ng.L (below).
//   lifted_origin: the same from p + lift (a shadow ray's start above a
//     smooth triangle, geometry/surface_mapping.h), the sum's rounding (an
//     ulp per component) added to the bound.
// I and N are unit vectors, N on the side I comes from (I.N <= 0).
#pragma once

#include <limits>

#include "simd/lanes.h"

namespace quiver {

inline namespace QUIVER_UNIT_NAMESPACE {

template <class F>
inline Vec3<F> reflect(const Vec3<F>& incident, const Vec3<F>& normal) {
  const F two_cos = F(2.f) * dot(incident, normal);
  return incident - normal * two_cos;
}

// T, with `transmitted` set in the lanes without total internal reflection.
template <class F>
inline Vec3<F> refract(const Vec3<F>& incident, const Vec3<F>& normal, const F& eta, Mask<F>& transmitted) {
  const F c1 = -dot(incident, normal);
  const F k = F(1.f) - eta * eta * (F(1.f) - c1 * c1);
  transmitted = !(k < F(0.f));
  return incident * eta + normal * (eta * c1 - sqrt(select(transmitted, k, F(0.f))));
}

// Rounding error of p = o + t d per component, from |o| and |t d|: a few
// ulps for the sum and product plus the kernels' error in t. With 0 the
// acne test (tests/integrator_render_test.cpp) fails at every scale; 64 is
// a margin, still ~4e-6 of the magnitudes involved.
inline constexpr float kOffsetErrorUlps = 64.f;

template <class F>
inline Vec3<F> hit_point_error(const Vec3<F>& origin, const Vec3<F>& direction, const F& t) {
  const F e(kOffsetErrorUlps * std::numeric_limits<float>::epsilon());
  return {e * (abs(origin.x) + abs(t * direction.x)), e * (abs(origin.y) + abs(t * direction.y)),
          e * (abs(origin.z) + abs(t * direction.z))};
}

// The next float from x toward the sign of `toward` (std::nextafter(x,
// +-inf)); x itself where toward is 0.
template <class F>
inline F next_float_away(const F& x, const F& toward) {
  const F up = next_float_up(x), down = -next_float_up(-x);
  return select(toward > F(0.f), up, select(toward < F(0.f), down, x));
}

// p moved to the side `side_normal` (unit) points to, clear of its error.
template <class F>
inline Vec3<F> offset_origin(const Vec3<F>& p, const Vec3<F>& error, const Vec3<F>& side_normal) {
  const F distance = abs(side_normal.x) * error.x + abs(side_normal.y) * error.y + abs(side_normal.z) * error.z;
  const Vec3<F> moved = p + side_normal * distance;
  return {next_float_away(moved.x, side_normal.x), next_float_away(moved.y, side_normal.y),
          next_float_away(moved.z, side_normal.z)};
}

template <class F>
inline F fresnel_reflectance(const Vec3<F>& incident, const Vec3<F>& normal, const F& eta) {
  const F c1 = -dot(incident, normal);
  const F k = F(1.f) - eta * eta * (F(1.f) - c1 * c1);
  const Mask<F> transmitted = !(k < F(0.f));
  const F c2 = sqrt(select(transmitted, k, F(0.f)));
  const F rs = (eta * c1 - c2) / (eta * c1 + c2), rp = (c1 - eta * c2) / (c1 + eta * c2);
  return select(transmitted, F(0.5f) * (rs * rs + rp * rp), F(1.f));
}

// How much of SurfaceMapping::shadow_lift a shadow ray takes: all of it
// where the face turns from the light (Ng.L <= 0), none where both N.L and
// Ng.L are at least kTerminatorBand, linearly between; a lift far from the
// terminator would only let thin parts of a coarse mesh shade themselves
// (Cycles restricts Hanika's lift the same way).
inline constexpr float kTerminatorBand = 0.1f;
template <class F>
inline F terminator_lift_share(const F& n_dot_l, const F& ng_dot_l) {
  const F band(kTerminatorBand);
  const F below = F(2.f) - (ng_dot_l + n_dot_l) / band, above = F(1.f) - ng_dot_l / band;
  return min(max(select(n_dot_l < band, below, above), F(0.f)), F(1.f));
}

template <class F>
inline Vec3<F> lifted_origin(const Vec3<F>& p, const Vec3<F>& error, const Vec3<F>& lift, const Vec3<F>& side_normal) {
  const Vec3<F> q = p + lift;
  const F ulp(std::numeric_limits<float>::epsilon());
  return offset_origin(q, {error.x + ulp * abs(q.x), error.y + ulp * abs(q.y), error.z + ulp * abs(q.z)}, side_normal);
}

}  // namespace QUIVER_UNIT_NAMESPACE
}  // namespace quiver
