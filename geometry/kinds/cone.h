// Ray / open truncated cone or cylinder (NFF `c`, no end caps) as a quadric
// restricted to a slab, after the classic ray-quadric test (Glassner, An
// Introduction to Ray Tracing, ch. 2), with pbrt-v4's stable quadratic roots
// and the origin shift of Haines et al., "Precision Improvements for
// Ray/Sphere Intersection" (Ray Tracing Gems, ch. 7).
// Per primitive: base center b, unit axis a, height h, base radius r0 and
// slope k = (r1 - r0) / h. A point P with s = (P - b).a lies on the surface
// iff |P - b|^2 - s^2 = (r0 + k s)^2, 0 <= s <= h and r0 + k s >= 0.
// The origin is first moved along the ray to t0 ~ its closest approach to b
// (t0 = -(o - b).d / d.d, any rounding of t0 is harmless: t = t0 + t'), so
// w = o + t0 d - b is small and nothing below cancels against |o - b|.
// With s(t') = wa + t' da and R = r0 + k wa:
//   A t'^2 + 2 B t' + C = 0,  A = |d_perp|^2 - (k da)^2,
//   B = w_perp.d_perp - R k da,  C = |w_perp|^2 - R^2,
// with the perpendicular parts as w x a, d x a (same lengths and dot
// products; d x a from cross_accurate, exact for d near the axis), and
// B^2 - A C = |R d_perp - k da w_perp|^2 - det(w, d, a)^2 (no B^2 vs A C
// cancellation at grazing rays). Roots: q = -(B + sign(B) sqrt(disc)),
// t1' = q / A, t2' = C / q.
// t-range: the nearest root with tmin < t, 0 <= s <= h and r0 + k s >= 0
// is the candidate (so a ray from inside, or through an open end, hits the
// inner wall; the mirrored nappe is rejected); it hits iff t < tmax.
// Degenerate cases: A == 0 (ray parallel to a cylinder's axis, or to a
// cone's generator line) leaves only t2' = C / q = -C / (2B), the linear
// root; q == 0 leaves only t1'. Divisions by zero are fed 1 and masked, so a
// ray parallel to a cylinder misses it (even on its surface) without NaN.
// A zero or non-finite d.d skips the shift (t0 = 0).
// Masks: only active lanes can hit.
// Output: ng = (P - b) - (s + k r) a = radial - k r a, the outward normal
// (length r sqrt(1 + k^2), not unit); at the apex point (radial == 0) ng is
// the axis pointing out of the tip. facing = -1 (NFF negative radii: inside
// visible) flips ng. u = s / h in [0, 1] along the axis (base 0, apex 1);
// v = 0 (the angle would need atan2, which has no lane op).
//
// Open cones and cylinders in SoA: base center, unit axis, height, base
// radius, slope and facing (see the kernel above).
// The kind's entry in the list of kinds (geometry/kinds.h) closes the file.
#pragma once

#include <array>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "geometry/box.h"
#include "geometry/build_report.h"
#include "geometry/desc_refs.h"
#include "geometry/hit.h"
#include "geometry/method_error.h"
#include "geometry/surface_mapping.h"
#include "geometry/soa.h"
#include "simd/ray.h"

namespace quiver {

enum class ConeMethod { quadric };

inline namespace QUIVER_UNIT_NAMESPACE {

template <class F>
struct ConeLanes {
  Vec3<F> base;  // center of the base circle
  Vec3<F> axis;  // unit, base to apex
  F height;      // > 0
  F radius0;     // radius at the base, >= 0
  F slope;       // k = (apex radius - base radius) / height
  F facing;      // +1 outside visible, -1 inside visible
};

// Per-ray setup: 1 / |d|^2 for the origin shift (0 where it is not finite).
template <class F>
struct ConeRay {
  Ray<F> ray;
  F inv_dir_length2;
};

struct ConeQuadric {
  template <class F>
  static ConeRay<F> prepare(const Ray<F>& ray) {
    const F dd = dot(ray.direction, ray.direction);
    const F inv = F(1.f) / select(dd > F(0.f), dd, F(1.f));
    return {ray, select(dd > F(0.f) && isfinite_lanes(inv), inv, F(0.f))};
  }

  template <class F>
  static Mask<F> intersect(const ConeRay<F>& prepared, const ConeLanes<F>& cone, const F& tmax,
                           const Mask<F>& active, Candidate<F>& out) {
    const Ray<F>& ray = prepared.ray;
    const Vec3<F>& a = cone.axis;
    const Vec3<F>& d = ray.direction;
    const F k = cone.slope;
    // Origin moved to ray(t0), t0 ~ closest approach to the base center:
    // w = o - b + t0 d stays small, t = t0 + t' is exact in t0.
    const Vec3<F> w_origin = ray.origin - cone.base;
    const F t0 = -dot(w_origin, d) * prepared.inv_dir_length2;
    const Vec3<F> w{fma(t0, d.x, w_origin.x), fma(t0, d.y, w_origin.y), fma(t0, d.z, w_origin.z)};
    // Axial coordinate s(t') = wa + t' da.
    const F wa = dot(w, a);
    const F da = dot(d, a);
    // Radial parts turned a quarter about the axis (d x a exact-ish for d near the axis).
    const Vec3<F> wr = cross(w, a);
    const Vec3<F> dr = cross_accurate(d, a);
    // Cone radius at s(0) and its rate along the ray.
    const F radius_at_origin = fma(k, wa, cone.radius0);
    const F kda = k * da;
    // Quadratic coefficients A, B, C.
    const F qa = fma(-kda, kda, dot(dr, dr));
    const F qb = fma(-radius_at_origin, kda, dot(wr, dr));
    const F qc = fma(-radius_at_origin, radius_at_origin, dot(wr, wr));
    // Discriminant B^2 - A C = |R dr - k da wr|^2 - det(w, d, a)^2.
    const Vec3<F> g{fma(radius_at_origin, dr.x, -(kda * wr.x)), fma(radius_at_origin, dr.y, -(kda * wr.y)),
                    fma(radius_at_origin, dr.z, -(kda * wr.z))};
    const F det = dot(cross(w, d), a);
    const F disc = fma(-det, det, dot(g, g));
    const Mask<F> real = active && disc >= F(0.f);
    if (none(real)) {
      out.t = out.u = out.v = F(0.f);
      out.ng = Vec3<F>(F(0.f), F(0.f), F(0.f));
      return real;
    }
    // Stable roots: q = -(B + sign(B) sqrt(disc)), t1' = q / A, t2' = C / q.
    const F root = sqrt(select(real, disc, F(0.f)));
    const F q = -(qb + select(qb < F(0.f), -root, root));
    const Mask<F> has_t1 = qa != F(0.f);
    const Mask<F> has_t2 = q != F(0.f);
    const F t1 = q / select(has_t1, qa, F(1.f));
    const F t2 = qc / select(has_t2, q, F(1.f));
    // Each root past tmin, inside the slab, on the real nappe.
    const F s1 = fma(t1, da, wa);
    const F s2 = fma(t2, da, wa);
    const Mask<F> ok1 = real && has_t1 && t0 + t1 > ray.tmin && s1 >= F(0.f) && s1 <= cone.height &&
                        fma(k, s1, cone.radius0) >= F(0.f);
    const Mask<F> ok2 = real && has_t2 && t0 + t2 > ray.tmin && s2 >= F(0.f) && s2 <= cone.height &&
                        fma(k, s2, cone.radius0) >= F(0.f);
    // Nearest valid root.
    const Mask<F> take1 = and_not(ok1, ok2 && t2 < t1);
    const F t_local = select(take1, t1, t2);
    const F s = select(take1, s1, s2);
    out.t = t0 + t_local;
    // Outward normal: hit - b - (s + k r) a.
    const Vec3<F> p{fma(t_local, d.x, w.x), fma(t_local, d.y, w.y), fma(t_local, d.z, w.z)};
    const F along = fma(k, fma(k, s, cone.radius0), s);
    const Vec3<F> n{fma(-along, a.x, p.x), fma(-along, a.y, p.y), fma(-along, a.z, p.z)};
    // Apex point: the axis out of the tip.
    const Mask<F> at_apex = n.x == F(0.f) && n.y == F(0.f) && n.z == F(0.f);
    const Vec3<F> tip_out = select(k < F(0.f), a, -a);
    out.ng = select(at_apex, tip_out, n) * cone.facing;
    out.u = s / cone.height;
    out.v = F(0.f);
    return (ok1 || ok2) && out.t < tmax;
  }
};

// The cone test: fn(kernel).
template <class Fn>
inline auto with_product_method(ConeMethod method, Fn fn) {
  switch (method) {
    case ConeMethod::quadric: break;
  }
  return fn(ConeQuadric{});
}

}  // namespace QUIVER_UNIT_NAMESPACE

// NFF `c`: an open cone (a cylinder when the radii are equal) from the base
// circle (center, radius) to the apex circle. NFF gives negative radii the
// meaning "inside visible"; both radii <= 0 (not both 0) is kept with |r| and
// facing -1, a positive and a negative radius together is dropped.
struct ConeDesc {
  Vec3<float> base;
  float base_radius;
  Vec3<float> apex;
  float apex_radius;
};

struct ConeSoA {
  AlignedFloats bx, by, bz, ax, ay, az, height, radius0, slope, facing;
  std::size_t count = 0;
  // Input index of each kept primitive (builders drop some), and the id of
  // primitive 0 in hits (a scene numbers its stores consecutively).
  std::vector<std::uint32_t> source;
  std::int32_t id_base = 0;

  // columns() hold every per-primitive field: a BVH reorders the store by
  // gathering them (geometry/bvh_store.h).
  static constexpr bool kColumnsHoldEveryField = true;

  std::size_t size() const { return count; }
  std::size_t memory_bytes() const;  // columns and source list
  // Every column, the one list of them (const for memory reports).
  template <class Self>
  static auto columns_of(Self& s) {
    return std::array{&s.bx, &s.by, &s.bz, &s.ax, &s.ay, &s.az, &s.height, &s.radius0, &s.slope, &s.facing};
  }
  auto columns() { return columns_of(*this); }
  auto columns() const { return columns_of(*this); }
  template <class F>
  ConeLanes<F> broadcast(std::size_t i) const {
    return {broadcast_vec3<F>(bx, by, bz, i), broadcast_vec3<F>(ax, ay, az, i), F(height[i]),
            F(radius0[i]),                    F(slope[i]),                      F(facing[i])};
  }
  template <class F>
  ConeLanes<F> load(std::size_t first) const {
    return {load_vec3_unaligned<F>(bx, by, bz, first),          load_vec3_unaligned<F>(ax, ay, az, first),
            load_lanes_unaligned<F>(height.data() + first),     load_lanes_unaligned<F>(radius0.data() + first),
            load_lanes_unaligned<F>(slope.data() + first),      load_lanes_unaligned<F>(facing.data() + first)};
  }
};

// Drops cones with a non-finite number (in the input or in the derived axis
// length) as non-finite; a zero (or subnormal) axis, both radii zero, radii of
// mixed sign, or a radius, slope or squared radius/slope that over- or
// underflows as degenerate.
ConeSoA build_cones(const DescRefs<ConeDesc>& cones, BuildReport& report);

// A conservative axis-aligned box of primitive i as stored (geometry/primitive_bounds.h).
Box primitive_box(const ConeSoA& store, std::size_t i);

// Its surface at a hit (geometry/surface_mapping.h).
void map_surface(const ConeSoA& store, const MappingQuery& query, SurfaceMapping& out);

// The cone in the scene's list of kinds (geometry/kinds.h).
struct ConeKind {
  static constexpr std::string_view name = "cone", plural = "cones";
  static constexpr bool bounded = true;
  using Method = ConeMethod;
  static constexpr ConeMethod product_method = ConeMethod::quadric;
  using Desc = ConeDesc;
  using Store = ConeSoA;
  static Store build(const DescRefs<Desc>& descs, BuildReport& report) { return build_cones(descs, report); }
  // add(point, margin) for points and margins whose boxes hold the described surface.
  template <class Add>
  static void extent(const Desc& d, Add add) {
    const double r = std::max(std::fabs(double(d.base_radius)), std::fabs(double(d.apex_radius)));
    add(d.base, r);
    add(d.apex, r);
  }
};

}  // namespace quiver
