// Ray differentials (Igehy 1999, "Tracing ray differentials"): each ray
// carries the change of its origin and unit direction over one sample
// spacing along the film's x and y. The camera gives them (integrator/
// camera.h); at a hit they are transferred to the point, then carried
// through reflection and refraction with the shading normal's own change.
// The point's change is the texture footprint (integrator/texture.h). One
// formula for every width (F = float, the reference, or a batch):
//   transfer: dP = dO + t dD + dt D, dt = -(dO + t dD).N / (D.N), N the
//     geometric normal (any length); D.N = 0 (grazing) gives an unbounded dP;
//   reflect: dR = dI - 2 [(I.N) dN + d(I.N) N], d(I.N) = dI.N + I.dN;
//   refract (T = eta I - mu N, mu = eta (I.N) - T.N, T.N = -sqrt k as in
//     optics.h): dT = eta dI - (mu dN + dmu N), dmu = (eta - eta^2 (I.N) /
//     (T.N)) d(I.N); total internal reflection lanes give finite garbage.
// I and N are unit, N on the side I comes from, as in optics.h.
#pragma once

#include "simd/lanes.h"

namespace quiver {

inline namespace QUIVER_UNIT_NAMESPACE {

template <class F>
inline Vec3<F> transfer_differential(const Vec3<F>& d_origin, const Vec3<F>& d_direction, const Vec3<F>& direction,
                                     const F& t, const Vec3<F>& normal) {
  const Vec3<F> moved = d_origin + d_direction * t;
  const F dt = -dot(moved, normal) / dot(direction, normal);
  return moved + direction * dt;
}

template <class F>
inline Vec3<F> reflect_differential(const Vec3<F>& incident, const Vec3<F>& d_incident, const Vec3<F>& normal,
                                    const Vec3<F>& d_normal) {
  const F cos_in = dot(incident, normal);
  const F d_cos_in = dot(d_incident, normal) + dot(incident, d_normal);
  return d_incident - (d_normal * cos_in + normal * d_cos_in) * F(2.f);
}

template <class F>
inline Vec3<F> refract_differential(const Vec3<F>& incident, const Vec3<F>& d_incident, const Vec3<F>& normal,
                                    const Vec3<F>& d_normal, const F& eta, const Vec3<F>& refracted) {
  const F cos_in = dot(incident, normal), cos_out = dot(refracted, normal);
  const F mu = eta * cos_in - cos_out;
  const F d_cos_in = dot(d_incident, normal) + dot(incident, d_normal);
  const F d_mu = (eta - eta * eta * cos_in / cos_out) * d_cos_in;
  return d_incident * eta - (d_normal * mu + normal * d_mu);
}

}  // namespace QUIVER_UNIT_NAMESPACE
}  // namespace quiver
