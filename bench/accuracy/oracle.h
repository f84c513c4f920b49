// The error oracle: the exact answer, to about 1e-30 relative, of "does this
// float ray hit this stored primitive, and at which t", computed in
// double-double (bench/accuracy/double_double.h) from the same float
// numbers the kernels read (the SoA store: sphere center and r^2, plane n
// and point (the seed's float d is an approximation of it), triangle
// vertices, polygon normal, first vertex and projected vertices, cone base,
// axis, height, radius and slope). Each reference follows its kernel's
// definition of the surface and of the t-range (geometry/*.h): the nearest
// root past tmin for spheres, edges and vertices inside for triangles, the
// half-open crossing rule for polygons, the slab and nappe for cones.
// clearance: how far the ray is from the other answer, relative to the
// primitive's size (0 on the boundary), so rays within rounding distance of
// a silhouette or edge can be told apart from real failures.
#pragma once

#include <cstddef>
#include <cstdint>

#include "geometry/kinds/cone.h"
#include "geometry/kinds/plane.h"
#include "geometry/kinds/polygon.h"
#include "geometry/kinds/sphere.h"
#include "geometry/kinds/triangle.h"

namespace quiver::accuracy {

struct Reference {
  bool hit = false;
  double t = 0.0;          // meaningful when hit
  double clearance = 0.0;  // relative distance to the hit/miss boundary, >= 0
  std::int32_t id = kNoHit;
};

// One primitive of a store (index i, before id_base).
//   sphere:   clearance |r^2 - dist(line, c)^2| / r^2;
//   plane:    clearance |n.d| / |d| (sine of the angle to the plane);
//   triangle: barycentric distance to the nearest edge (inside: min, outside: max of -lambda);
//   polygon:  2D distance to the nearest edge / the polygon's extent;
//   cone:     min of the discriminant's share |B^2 - AC| / (A r_max^2), the slab margins s/h, 1 - s/h
//             of the root taken and of a nearer root rejected at a rim.
Reference reference(const Ray<float>& ray, const SphereSoA& spheres, std::size_t i);
Reference reference(const Ray<float>& ray, const PlaneSoA& planes, std::size_t i);
Reference reference(const Ray<float>& ray, const TriangleSoA& triangles, std::size_t i);
Reference reference(const Ray<float>& ray, const PolygonSoA& polygons, std::size_t i);
Reference reference(const Ray<float>& ray, const ConeSoA& cones, std::size_t i);

// The closest hit over a store (ties to the smaller id, as the streams); a
// miss carries the smallest clearance of any primitive, a hit its own.
template <class S>
Reference closest_reference(const Ray<float>& ray, const S& store) {
  Reference best;
  double miss_clearance = 1e300;
  for (std::size_t i = 0; i < store.size(); ++i) {
    Reference r = reference(ray, store, i);
    if (!r.hit) {
      if (r.clearance < miss_clearance) miss_clearance = r.clearance;
      continue;
    }
    if (!best.hit || r.t < best.t) {
      best = r;
      best.id = store.id_base + static_cast<std::int32_t>(i);
    }
  }
  if (!best.hit) best.clearance = store.size() == 0 ? 1e300 : miss_clearance;
  return best;
}

// Spacing of floats at |x| (the float ulp of x; the smallest subnormal step at 0).
double float_ulp(double x);
// |t - reference| in float ulps of the reference.
double ulp_error(double t, double reference_t);

}  // namespace quiver::accuracy
