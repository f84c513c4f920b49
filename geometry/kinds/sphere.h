// Ray / sphere, three methods (all with the same contract):
//   SphereAlgebraic: the seed's quadratic (Haines, "Essential Ray Tracing
//     Algorithms", in Glassner (ed.), An Introduction to Ray Tracing, ch. 2):
//     L = o - c, A = d.d, B = 2 d.L, C = L.L - r^2, disc = B^2 - 4AC,
//     t0,1 = (-B -+ sqrt(disc)) * (1 / 2A), 1 / 2A once per ray in prepare().
//     Plain arithmetic, no fma.
//   SphereGeometric: the seed's geometric method, same chapter: L = c - o,
//     t_ca = L.d^, d^2 = L.L - t_ca^2, t_hc = sqrt(r^2 - d^2), roots
//     (t_ca -+ t_hc) * (1 / |d|). d^ = d / |d| and 1 / |d| are computed once
//     per ray in prepare(), so t_ca and t_hc are distances and t is in units of d.
//   SphereRobust: Haines, Guenther, Akenine-Moeller, "Precision Improvements
//     for Ray/Sphere Intersection", Ray Tracing Gems (2019), ch. 7: with
//     f = o - c, a = d.d, h = f.d, the discriminant is a (r^2 - |l|^2),
//     l = f - (h/a) d (center to the chord's midpoint, by fma so the large
//     parallel parts cancel before rounding); the roots are q/a and c/q with
//     q = -(h + sign(h) sqrt(disc)), c = f.f - r^2 (no cancellation in either).
//     Beyond the chapter: the part of l left along d by the rounding of h/a
//     (about eps |f|, enough for false misses once |f| is many radii) is
//     projected out inside the discriminant, disc = a (r^2 - |l|^2) + (l.d)^2.
//     That makes the rounding of h/a harmless, so it is h * (1/a) with 1/a
//     from prepare(); the roots are q * (1/a) and the one true division c / q.
// Per-test divisions are replaced by per-ray reciprocals (prepare()) and a
// stored 1/r, except robust's c / q.
// t-range: the nearer root if it is > tmin, else the farther one; hit iff that
// t is in (tmin, tmax). So an origin inside the sphere hits the far side, in
// either orientation, and the seed's inside/outside test and "t_ca < 0" early
// out are replaced by this choice (equivalent for tmin = 0 up to rounding).
// Tangent rays: a computed discriminant >= 0 is a hit, with t the (double)
// root at the touching point, so an exact tangent (o = (1,0,-5), d = +z, unit
// sphere) hits in every method. Near tangency rounding decides: the
// algebraic and geometric methods can disagree with exact arithmetic only for
// lines within 2e-4 r of tangency (their discriminants cancel), robust only
// within 1e-6 r (the bands tests/geometry_sphere_test.cpp checks in
// SphereStability.GrazingRays).
// Masks: only active lanes hit; the kernel returns early (no_hit) once no
// lane has a real root. A direction whose d.d is 0 (or underflows),
// Inf or NaN misses. sqrt and the divisions are fed safe values (0, 1) in lanes
// that miss, so no lane needs a NaN or a division by zero.
// Output: ng = (o + t d - c) / r, the outward normal (unit up to rounding, never
// flipped toward the ray), evaluated as fma(d, t, o - c) * (1/r), 1/r stored
// per sphere. u = v = 0:
// spherical texture coordinates are derived from ng at shading time.
//
// Spheres in SoA: center (cx, cy, cz), r^2 and 1/r.
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

enum class SphereMethod { algebraic, geometric, robust };

inline namespace QUIVER_UNIT_NAMESPACE {

template <class F>
struct SphereLanes {
  Vec3<F> center;
  F radius2;         // radius * radius, a normal float
  F inverse_radius;  // 1 / radius
};

namespace sphere_detail {

// d.d is a usable length: not 0, not underflowed to 0, not Inf or NaN.
template <class F>
inline Mask<F> direction_ok(const F& dd) {
  return dd > F(0.f) && isfinite_lanes(dd);
}

// (o + t d - c) / r from f = o - c: one rounding per component, then a
// multiply by the stored 1/r (within 1.5 ulp of dividing).
template <class F>
inline Vec3<F> outward_normal(const Vec3<F>& f, const Vec3<F>& d, const F& t, const F& inv_r) {
  return {fma(d.x, t, f.x) * inv_r, fma(d.y, t, f.y) * inv_r, fma(d.z, t, f.z) * inv_r};
}

// Nearer root if it lies beyond tmin, else the farther one.
template <class F>
inline F pick_root(const F& near, const F& far, const F& tmin) {
  return select(near > tmin, near, far);
}

}  // namespace sphere_detail

// Per-ray values of the algebraic and robust methods: A = d.d and its validity.
template <class F>
struct SphereRay {
  Ray<F> ray;
  F dd;            // d.d, replaced by 1 where not direction_ok
  F inv_dd;        // 1 / dd
  Mask<F> usable;  // direction_ok(d.d)
};

// Per-ray values of the geometric method: the unit direction and |d|.
template <class F>
struct SphereUnitRay {
  Ray<F> ray;
  Vec3<F> unit;   // d / |d| (0 where not usable)
  F inv_length;   // 1 / |d|, 1 where not usable
  Mask<F> usable;
};

template <class F>
inline SphereRay<F> prepare_sphere_ray(const Ray<F>& ray) {
  const F dd = dot(ray.direction, ray.direction);
  const Mask<F> usable = sphere_detail::direction_ok(dd);
  const F safe_dd = select(usable, dd, F(1.f));
  return {ray, safe_dd, F(1.f) / safe_dd, usable};
}

// Base of the methods that work with A = d.d and 1/A per ray.
struct PreparesSphereRay {
  template <class F>
  static SphereRay<F> prepare(const Ray<F>& ray) {
    return prepare_sphere_ray(ray);
  }
};

struct SphereAlgebraic : PreparesSphereRay {
  template <class F>
  static Mask<F> intersect(const SphereRay<F>& r, const SphereLanes<F>& s, const F& tmax,
                           const Mask<F>& active, Candidate<F>& out) {
    const Ray<F>& ray = r.ray;
    const Vec3<F> L = ray.origin - s.center;
    const F A = r.dd;
    const F B = F(2.f) * dot(ray.direction, L);
    const F C = dot(L, L) - s.radius2;
    const F disc = B * B - F(4.f) * A * C;  // the seed's discriminant
    const Mask<F> real = active && r.usable && disc >= F(0.f);
    if (none(real)) return no_hit(real, out);
    const F root = sqrt(select(real, disc, F(0.f)));
    const F inv_two_a = F(0.5f) * r.inv_dd;  // exact: a power-of-two scale
    const F t0 = (-B - root) * inv_two_a;
    const F t1 = (-B + root) * inv_two_a;
    out.t = sphere_detail::pick_root(t0, t1, ray.tmin);
    out.u = F(0.f);
    out.v = F(0.f);
    out.ng = sphere_detail::outward_normal(L, ray.direction, out.t, s.inverse_radius);
    return real && out.t > ray.tmin && out.t < tmax;
  }
};

struct SphereGeometric {
  template <class F>
  static SphereUnitRay<F> prepare(const Ray<F>& ray) {
    const F dd = dot(ray.direction, ray.direction);
    const Mask<F> usable = sphere_detail::direction_ok(dd);
    const F length = sqrt(select(usable, dd, F(1.f)));
    const Vec3<F> unit = select(usable, ray.direction / length, Vec3<F>(F(0.f), F(0.f), F(0.f)));
    return {ray, unit, F(1.f) / length, usable};
  }

  template <class F>
  static Mask<F> intersect(const SphereUnitRay<F>& r, const SphereLanes<F>& s, const F& tmax,
                           const Mask<F>& active, Candidate<F>& out) {
    const Ray<F>& ray = r.ray;
    const Vec3<F> L = s.center - ray.origin;
    const F t_ca = dot(L, r.unit);             // distance to the point closest to c
    const F d2 = dot(L, L) - t_ca * t_ca;      // squared distance of the line from c
    const F t_hc2 = s.radius2 - d2;            // squared half chord
    const Mask<F> real = active && r.usable && t_hc2 >= F(0.f);
    if (none(real)) return no_hit(real, out);
    const F t_hc = sqrt(select(real, t_hc2, F(0.f)));
    const F t0 = (t_ca - t_hc) * r.inv_length;
    const F t1 = (t_ca + t_hc) * r.inv_length;
    out.t = sphere_detail::pick_root(t0, t1, ray.tmin);
    out.u = F(0.f);
    out.v = F(0.f);
    out.ng = sphere_detail::outward_normal(-L, ray.direction, out.t, s.inverse_radius);
    return real && out.t > ray.tmin && out.t < tmax;
  }
};

struct SphereRobust : PreparesSphereRay {
  template <class F>
  static Mask<F> intersect(const SphereRay<F>& r, const SphereLanes<F>& s, const F& tmax,
                           const Mask<F>& active, Candidate<F>& out) {
    const Ray<F>& ray = r.ray;
    const Vec3<F>& d = ray.direction;
    const Vec3<F> f = ray.origin - s.center;
    const F a = r.dd;
    const F h = fma(f.x, d.x, fma(f.y, d.y, f.z * d.z));  // half of b = 2 f.d
    const F along = h * r.inv_dd;  // t of the point closest to c (its rounding is projected out below)
    // l = f - (h/a) d: fma cancels the large parallel parts before rounding.
    const Vec3<F> l{fma(-along, d.x, f.x), fma(-along, d.y, f.y), fma(-along, d.z, f.z)};
    const F r2_minus_l2 = fma(-l.x, l.x, fma(-l.y, l.y, fma(-l.z, l.z, s.radius2)));
    // disc = h^2 - a c = a (r^2 - |l_perp|^2); the part of l left along d by the
    // rounding of h/a is removed here: |l_perp|^2 = |l|^2 - (l.d)^2 / a.
    const F ld = dot(l, d);
    const F disc = fma(ld, ld, a * r2_minus_l2);
    const Mask<F> real = active && r.usable && disc >= F(0.f);
    if (none(real)) return no_hit(real, out);
    const F root = sqrt(select(real, disc, F(0.f)));
    const F c = fma(f.x, f.x, fma(f.y, f.y, fma(f.z, f.z, -s.radius2)));
    const F q = -(h + select(h < F(0.f), -root, root));  // no cancellation: same signs
    const Mask<F> q_nonzero = q != F(0.f);                // q = 0 only at a double root t = 0
    const F ta = q * r.inv_dd;
    const F tb = select(q_nonzero, c / select(q_nonzero, q, F(1.f)), ta);
    out.t = sphere_detail::pick_root(min(ta, tb), max(ta, tb), ray.tmin);
    out.u = F(0.f);
    out.v = F(0.f);
    out.ng = sphere_detail::outward_normal(f, d, out.t, s.inverse_radius);
    return real && out.t > ray.tmin && out.t < tmax;
  }
};

// The product's sphere tests: fn(kernel) for algebraic and robust (the
// geometric test is the study's: tests/support/study_streams.h).
template <class Fn>
inline auto with_product_method(SphereMethod method, Fn fn) {
  switch (method) {
    case SphereMethod::algebraic: return fn(SphereAlgebraic{});
    case SphereMethod::robust: return fn(SphereRobust{});
    case SphereMethod::geometric: break;
  }
  throw_study_method("sphere", "geometric");
}

}  // namespace QUIVER_UNIT_NAMESPACE

struct SphereDesc {
  Vec3<float> center;
  float radius;
};

struct SphereSoA {
  AlignedFloats cx, cy, cz, r2, inv_r;
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
  static auto columns_of(Self& s) { return std::array{&s.cx, &s.cy, &s.cz, &s.r2, &s.inv_r}; }
  auto columns() { return columns_of(*this); }
  auto columns() const { return columns_of(*this); }
  template <class F>
  SphereLanes<F> broadcast(std::size_t i) const {
    return {broadcast_vec3<F>(cx, cy, cz, i), F(r2[i]), F(inv_r[i])};
  }
  template <class F>
  SphereLanes<F> load(std::size_t first) const {
    return {load_vec3_unaligned<F>(cx, cy, cz, first), load_lanes_unaligned<F>(r2.data() + first),
            load_lanes_unaligned<F>(inv_r.data() + first)};
  }
};

// Drops spheres with a non-finite center or radius, or whose r^2 overflows
// (non-finite); and spheres with a radius <= 0 or whose r^2 is below the
// smallest normal float (degenerate). Negative radii are not mirrored.
SphereSoA build_spheres(const DescRefs<SphereDesc>& spheres, BuildReport& report);

// A conservative axis-aligned box of primitive i as stored (geometry/primitive_bounds.h).
Box primitive_box(const SphereSoA& store, std::size_t i);

// Its surface at a hit (geometry/surface_mapping.h).
void map_surface(const SphereSoA& store, const MappingQuery& query, SurfaceMapping& out);

// The sphere in the scene's list of kinds (geometry/kinds.h).
struct SphereKind {
  static constexpr std::string_view name = "sphere", plural = "spheres";
  static constexpr bool bounded = true;
  using Method = SphereMethod;
  // The default; a scene whose rays all start near its spheres may take
  // the algebraic test (integrator/scene_intersector.h).
  static constexpr SphereMethod product_method = SphereMethod::robust;
  using Desc = SphereDesc;
  using Store = SphereSoA;
  static Store build(const DescRefs<Desc>& descs, BuildReport& report) { return build_spheres(descs, report); }
  // add(point, margin) for points and margins whose boxes hold the described surface.
  template <class Add>
  static void extent(const Desc& d, Add add) {
    add(d.center, std::fabs(double(d.radius)));
  }
};

}  // namespace quiver
