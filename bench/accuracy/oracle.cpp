// The double-double references of bench/accuracy/oracle.h. Every input is a
// float, so differences of inputs are exact (two_sum) and the rest carries a
// relative error near 1e-31 of the magnitudes involved: far below the
// float kernels' 6e-8 even after the 1e14-fold cancellations of a ray from
// 1e7 radii away.
#include "bench/accuracy/oracle.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bench/accuracy/double_double.h"

namespace quiver::accuracy {
namespace {

using DD = DoubleDouble;

DDVec3 exact(const Vec3<float>& v) { return {DD(v.x), DD(v.y), DD(v.z)}; }

// a - b exactly, for float inputs.
DDVec3 exact_difference(const Vec3<float>& a, const Vec3<float>& b) {
  return {two_sum(a.x, -double(b.x)), two_sum(a.y, -double(b.y)), two_sum(a.z, -double(b.z))};
}

double to_double(const DD& x) { return x.to_double(); }

// The roots of A t^2 + 2 B t + C = 0 without cancellation: q = -(B + sign(B) sqrt(disc)),
// t1 = q / A, t2 = C / q; a missing root (A == 0 or q == 0) is NaN.
struct Roots {
  double near = std::numeric_limits<double>::quiet_NaN(), far = std::numeric_limits<double>::quiet_NaN();
};
Roots stable_roots(const DD& a, const DD& b, const DD& c, const DD& disc) {
  const DD root = sqrt(disc);
  const DD q = -(b.hi < 0.0 ? b - root : b + root);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double t1 = a.hi != 0.0 ? to_double(q / a) : nan;
  const double t2 = q.hi != 0.0 ? to_double(c / q) : (a.hi != 0.0 ? to_double(-b / a) : nan);
  Roots r;
  if (std::isnan(t1) || (!std::isnan(t2) && t2 < t1)) {
    r.near = t2;
    r.far = t1;
  } else {
    r.near = t1;
    r.far = t2;
  }
  return r;
}

Vec3<float> float_vertex(const AlignedFloats& x, const AlignedFloats& y, const AlignedFloats& z, std::size_t i) {
  return {x[i], y[i], z[i]};
}

// Where the ray meets the plane n.P + d = 0 (stored n and d): t = -(d + n.o) / n.dir.
struct PlaneCrossing {
  DD denominator;  // n.dir; 0 for a parallel ray (then t is not set)
  DD t;
};
// The plane through the stored point p with the stored normal: d = -n.p exactly.
PlaneCrossing cross_plane(const Ray<float>& ray, const Vec3<float>& normal, const Vec3<float>& point) {
  const DDVec3 n = exact(normal);
  PlaneCrossing c{dot(n, exact(ray.direction)), DD(0.0)};
  if (c.denominator.hi != 0.0) c.t = dot(n, exact_difference(point, ray.origin)) / c.denominator;
  return c;
}

}  // namespace

double float_ulp(double x) {
  const double a = std::fabs(x);
  if (a < double(std::numeric_limits<float>::min())) return double(std::numeric_limits<float>::denorm_min());
  int exponent = 0;
  std::frexp(a, &exponent);  // a = m 2^exponent, m in [0.5, 1)
  return std::ldexp(1.0, exponent - 24);
}

double ulp_error(double t, double reference_t) { return std::fabs(t - reference_t) / float_ulp(reference_t); }

Reference reference(const Ray<float>& ray, const SphereSoA& spheres, std::size_t i) {
  const Vec3<float> center = float_vertex(spheres.cx, spheres.cy, spheres.cz, i);
  const DD r2(spheres.r2[i]);
  const DDVec3 f = exact_difference(ray.origin, center);
  const DDVec3 d = exact(ray.direction);
  // A t^2 + 2 h t + c = 0 with A = d.d, h = f.d, c = f.f - r^2.
  const DD a = dot(d, d);
  const DD h = dot(f, d);
  const DD c = dot(f, f) - r2;
  const DD disc = h * h - a * c;  // = A (r^2 - dist(line, center)^2)
  Reference ref;
  if (a.hi == 0.0) return ref;
  ref.clearance = std::fabs(to_double(disc / (a * r2)));
  if (disc.hi < 0.0) return ref;
  const Roots roots = stable_roots(a, h, c, disc);
  const double t = roots.near > ray.tmin ? roots.near : roots.far;
  ref.t = t;
  ref.hit = t > ray.tmin && t < ray.tmax;
  return ref;
}

Reference reference(const Ray<float>& ray, const PlaneSoA& planes, std::size_t i) {
  const Vec3<float> normal = float_vertex(planes.nx, planes.ny, planes.nz, i);
  const PlaneCrossing crossing = cross_plane(ray, normal, float_vertex(planes.px, planes.py, planes.pz, i));
  Reference ref;
  const double d_length = std::sqrt(to_double(dot(exact(ray.direction), exact(ray.direction))));
  const double n_length = std::sqrt(to_double(dot(exact(normal), exact(normal))));
  if (d_length == 0.0) return ref;
  ref.clearance = std::fabs(to_double(crossing.denominator)) / (d_length * n_length);
  if (crossing.denominator.hi == 0.0) return ref;
  ref.t = to_double(crossing.t);
  ref.hit = ref.t > ray.tmin && ref.t < ray.tmax;
  return ref;
}

Reference reference(const Ray<float>& ray, const TriangleSoA& triangles, std::size_t i) {
  // Vertices relative to the origin (exact), then the signed volumes of the
  // line with each edge: lambda_k weighs vertex k, their sum is n.d.
  const DDVec3 a = exact_difference(float_vertex(triangles.v0x, triangles.v0y, triangles.v0z, i), ray.origin);
  const DDVec3 b = exact_difference(float_vertex(triangles.v1x, triangles.v1y, triangles.v1z, i), ray.origin);
  const DDVec3 c = exact_difference(float_vertex(triangles.v2x, triangles.v2y, triangles.v2z, i), ray.origin);
  const DDVec3 d = exact(ray.direction);
  const DD l0 = dot(cross(b, c), d), l1 = dot(cross(c, a), d), l2 = dot(cross(a, b), d);
  const DD det = l0 + l1 + l2;
  Reference ref;
  if (det.hi == 0.0) return ref;
  const double b0 = to_double(l0 / det), b1 = to_double(l1 / det), b2 = to_double(l2 / det);
  const bool inside = b0 >= 0.0 && b1 >= 0.0 && b2 >= 0.0;
  ref.clearance = inside ? std::min({b0, b1, b2}) : std::max({-b0, -b1, -b2});
  if (!inside) return ref;
  // t = n.a / n.d with n = (b - a) x (c - a).
  const DDVec3 n = cross(b - a, c - a);
  ref.t = to_double(dot(n, a) / dot(n, d));
  ref.hit = ref.t > ray.tmin && ref.t < ray.tmax;
  return ref;
}

Reference reference(const Ray<float>& ray, const PolygonSoA& polygons, std::size_t i) {
  // The plane through the stored first vertex (the kernel's t is anchored there).
  const PlaneCrossing crossing =
      cross_plane(ray, float_vertex(polygons.nx, polygons.ny, polygons.nz, i),
                  float_vertex(polygons.px, polygons.py, polygons.pz, polygons.first_vertex[i]));
  Reference ref;
  if (crossing.denominator.hi == 0.0) return ref;
  const DD t = crossing.t;
  const DDVec3 o = exact(ray.origin), d = exact(ray.direction);
  ref.t = to_double(t);
  // The hit point in the polygon's projection, relative to its first vertex.
  const int axis_u = polygons.axis_u[i], axis_v = polygons.axis_v[i];
  auto component = [](const DDVec3& vec, int axis) { return axis == 0 ? vec.x : (axis == 1 ? vec.y : vec.z); };
  const DD u = component(o, axis_u) + t * component(d, axis_u) - DD(polygons.origin_u[i]);
  const DD v = component(o, axis_v) + t * component(d, axis_v) - DD(polygons.origin_v[i]);
  // Even-odd crossing test with the kernel's half-open rule, exactly.
  const std::size_t first = polygons.first_vertex[i];
  const int count = polygons.vertex_count[i];
  bool inside = false;
  double nearest_edge = 1e300;
  const double pu_point = to_double(u), pv_point = to_double(v);
  for (int k = 0; k < count; ++k) {
    const std::size_t ia = first + std::size_t((k + count - 1) % count), ib = first + std::size_t(k);
    const DD au(polygons.pu[ia]), av(polygons.pv[ia]), bu(polygons.pu[ib]), bv(polygons.pv[ib]);
    const bool a_above = av > v, b_above = bv > v;
    if (a_above != b_above) {
      const DD side = (v - av) * (bu - au) - (u - au) * (bv - av);
      if ((side.hi > 0.0) == b_above) inside = !inside;
    }
    // Distance of the point to the segment a-b (double suffices for a clearance).
    const double ex = to_double(bu - au), ey = to_double(bv - av);
    const double wx = pu_point - au.hi, wy = pv_point - av.hi;
    const double length2 = ex * ex + ey * ey;
    const double s = length2 > 0.0 ? std::clamp((wx * ex + wy * ey) / length2, 0.0, 1.0) : 0.0;
    nearest_edge = std::min(nearest_edge, std::hypot(wx - s * ex, wy - s * ey));
  }
  const double extent = std::max(polygons.umax[i] - polygons.umin[i], polygons.vmax[i] - polygons.vmin[i]);
  ref.clearance = nearest_edge / extent;
  ref.hit = inside && ref.t > ray.tmin && ref.t < ray.tmax;
  return ref;
}

Reference reference(const Ray<float>& ray, const ConeSoA& cones, std::size_t i) {
  // The kernel's surface: |(P - b) x a|^2 = (r0 + k s)^2, s = (P - b).a,
  // 0 <= s <= h, r0 + k s >= 0, with P - b = w + t d, w = o - b exact.
  const DDVec3 w = exact_difference(ray.origin, float_vertex(cones.bx, cones.by, cones.bz, i));
  const DDVec3 axis = exact(float_vertex(cones.ax, cones.ay, cones.az, i));
  const DDVec3 d = exact(ray.direction);
  const DD k(cones.slope[i]), r0(cones.radius0[i]);
  const double height = cones.height[i];
  const DDVec3 wr = cross(w, axis), dr = cross(d, axis);
  const DD wa = dot(w, axis), da = dot(d, axis);
  const DD radius_at_origin = r0 + k * wa, kda = k * da;
  // A t^2 + 2 B t + C = 0.
  const DD qa = dot(dr, dr) - kda * kda;
  const DD qb = dot(wr, dr) - radius_at_origin * kda;
  const DD qc = dot(wr, wr) - radius_at_origin * radius_at_origin;
  const DD disc = qb * qb - qa * qc;
  const double r_max = std::max(double(cones.radius0[i]), std::fabs(double(cones.radius0[i]) + double(cones.slope[i]) * height));
  const double a_scale = std::max(std::fabs(to_double(qa)), 1e-300);
  const double disc_share = std::fabs(to_double(disc)) / (a_scale * r_max * r_max);
  Reference ref;
  ref.clearance = disc_share;
  if (disc.hi < 0.0) return ref;
  const Roots roots = stable_roots(qa, qb, qc, disc);
  double slab_margin = 1e300;
  for (const double t : {roots.near, roots.far}) {
    if (std::isnan(t)) continue;
    const double s = to_double(wa + DD(t) * da);
    const double margin = std::min(s / height, 1.0 - s / height);
    const bool on_nappe = double(cones.radius0[i]) + double(cones.slope[i]) * s >= 0.0;
    if (t > ray.tmin && margin >= 0.0 && on_nappe) {
      ref.t = t;
      ref.hit = t < ray.tmax;
      // A nearer root rejected by a hair (a ray past the rim) is as close to the other answer.
      ref.clearance = std::min({disc_share, margin, slab_margin});
      return ref;
    }
    slab_margin = std::min(slab_margin, std::fabs(margin));
  }
  ref.clearance = std::min(disc_share, slab_margin);
  return ref;
}

}  // namespace quiver::accuracy
