// The frame of a hit, one formula for every width (surface_at for one ray,
// the wave's lanes for a packet): the point p = o + t d, its rounding-error
// bound (optics.h), the unit geometric normal turned toward the ray, and the
// shading normal on the same side (interpolated where the primitive has one,
// else the geometric normal); entering: the ray arrives on the primitive's
// outward side.
#pragma once

#include "geometry/hit.h"
#include "integrator/optics.h"
#include "simd/ray.h"

namespace quiver {

template <class F>
struct SurfaceFrame {
  Vec3<F> position;
  Vec3<F> error;      // bound on |position - exact hit| per component
  Vec3<F> geometric;  // unit geometric normal facing the incoming ray
  Vec3<F> shading;    // unit shading normal on the same side
  Mask<F> entering;
};

inline namespace QUIVER_UNIT_NAMESPACE {

template <class F>
inline Vec3<F> hit_position(const Ray<F>& ray, const F& t) {
  return ray.origin + ray.direction * t;
}

// smooth: the lanes whose shading normal is `interpolated` (unit, in the
// primitive's orientation); the others shade with the geometric normal.
template <class F>
inline SurfaceFrame<F> surface_frame(const Ray<F>& ray, const Hit<F>& hit, const Mask<F>& smooth,
                                     const Vec3<F>& interpolated) {
  SurfaceFrame<F> s;
  s.position = hit_position(ray, hit.t);
  s.error = hit_point_error(ray.origin, ray.direction, hit.t);
  const Vec3<F> outward = normalize(hit.ng);
  const Vec3<F> shading = select(smooth, interpolated, outward);
  s.entering = dot(ray.direction, outward) < F(0.f);
  s.geometric = select(s.entering, outward, -outward);
  s.shading = select(dot(shading, s.geometric) < F(0.f), -shading, shading);
  return s;
}

}  // namespace QUIVER_UNIT_NAMESPACE
}  // namespace quiver
