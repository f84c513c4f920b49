// Ray / infinite plane, the seed's formula: the plane is n.P + d = 0 with
// unit n, so t = -(d + n.o) / (n.dir).
// t-range: hit iff tmin < t < tmax. A ray parallel to the plane (n.dir == 0)
// misses, even when its origin lies on the plane; the division is then fed
// 1 so no lane makes a NaN or a division by zero.
// Masks: only active lanes can hit. u = v = 0 (planar texture coordinates
// come from the hit point at shading); ng = n (both sides hit).
#pragma once

#include "geometry/hit.h"
#include "simd/ray.h"

namespace quiver {

inline namespace QUIVER_UNIT_NAMESPACE {

template <class F>
struct PlaneLanes {
  Vec3<F> normal;  // unit length
  F d;             // n.P + d = 0 on the plane
};

// t where the ray meets the plane n.P + d = 0; `crosses` marks the lanes
// not parallel to it (the others divide by 1 and must be masked off).
template <class F>
inline F plane_crossing(const Ray<F>& ray, const Vec3<F>& normal, const F& d, Mask<F>& crosses) {
  const F denom = dot(normal, ray.direction);
  crosses = denom != F(0.f);
  const F numer = -(d + dot(normal, ray.origin));
  return numer / select(crosses, denom, F(1.f));
}

struct PlaneSeed : RayAsIs {
  template <class F>
  static Mask<F> intersect(const Ray<F>& ray, const PlaneLanes<F>& plane, const F& tmax,
                           const Mask<F>& active, Candidate<F>& out) {
    Mask<F> crosses;
    out.t = plane_crossing(ray, plane.normal, plane.d, crosses);
    out.u = F(0.f);
    out.v = F(0.f);
    out.ng = plane.normal;
    return active && crosses && out.t > ray.tmin && out.t < tmax;
  }
};

}  // namespace QUIVER_UNIT_NAMESPACE

}  // namespace quiver
