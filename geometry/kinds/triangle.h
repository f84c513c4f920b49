// Ray / triangle, two methods, both two-sided.
//
// TriangleMollerTrumbore: Moller & Trumbore, "Fast, Minimum Storage
//   Ray/Triangle Intersection", JGT 2(1), 1997. Cramer's rule in the basis
//   e1 = v1-v0, e2 = v2-v0: p = d x e2, det = e1.p, T = o-v0, q = T x e1,
//   u = T.p/det, v = d.q/det, t = e2.q/det (as products with 1/det, like the
//   paper's code). Epsilon-free: only det == 0 misses (1 is fed to the
//   division). Not watertight: a ray through a shared edge can miss both
//   triangles (tests/geometry_triangle_test.cpp finds such rays).
// TriangleWatertight: Woop, Benthin & Wald, "Watertight Ray/Triangle
//   Intersection", JCGT 2(1), 2013. prepare(): per lane kz = argmax|d| (ties
//   to z, then y), kx, ky cyclic after it and swapped when d[kz] < 0, shear
//   Sx = d[kx]/d[kz], Sy = d[ky]/d[kz], Sz = 1/d[kz]; the per-lane axis
//   choice is masks applied with selects. Edge functions w0, w1, w2 (w_i
//   weighs vertex i) are unfused products, so a shared edge gives exactly
//   opposite values, and by monotonic rounding the right sign or 0. A 0 is
//   recomputed with difference_of_products (error <= 2 ulp, so the exact
//   sign unless the products underflow) in place of the paper's double.
//   Deviations: the shear uses fma (one rounding instead of two, so fewer
//   misses far from the origin), and t is range-tested after the division,
//   not as the paper's scaled t xor sign(det), so (tmin, tmax) is exact and the
//   stream orders agree bit for bit; the division still waits until some
//   lane passes the edge tests.
//   Axes: when every lane shares kz and the swap (always for one ray, for a
//   scan's broadcast ray and for most coherent packets) the permutation is
//   fixed per packet at compile time (AxesFixed) instead of 18 per-lane
//   selects per test (AxesPerLane). Both pick the same floats, so the bits
//   are the same either way. with_fixed_axes prepares one ray once and hands
//   its frame to the caller as a type, so a walk over many scan blocks (the
//   single-ray BVH walk) chooses it once per ray; prepare_lanes and
//   for_each_lane_by_frame do the same for a packet's rays at once.
//
// Both: hit iff active, inside (edges and vertices included), det != 0,
// tmin < t < tmax and ng != 0 (a triangle whose computed ng is exactly zero,
// e.g. a repeated vertex or exactly proportional edges, never hits).
// out.u, out.v weigh v1 and v2: hit = (1-u-v) v0 + u v1 + v v2.
// out.ng = (v1-v0) x (v2-v0), not unit, not flipped toward the ray.
// Each kernel returns early (no_hit) once no lane passes its inside test
// (the watertight test again once none is within (tmin, tmax)); that
// changes no lane's result.
//
// Triangles in SoA: vertex columns v0, v1, v2 (9), and optional per-vertex
// shading normals (9) and texture coordinates (6), empty when no input
// triangle has them.
// The kind's entry in the list of kinds (geometry/kinds.h) closes the file.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
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

enum class TriangleMethod { moller_trumbore, watertight };

inline namespace QUIVER_UNIT_NAMESPACE {

template <class F>
struct TriangleLanes {
  Vec3<F> v0, v1, v2;
};

namespace triangle_detail {

template <class F>
inline Mask<F> nonzero(const Vec3<F>& a) {
  return a.x != F(0.f) || a.y != F(0.f) || a.z != F(0.f);
}

// (a && m) || (b && !m) for masks.
template <class F>
inline Mask<F> choose(const Mask<F>& m, const Mask<F>& a, const Mask<F>& b) {
  return (m && a) || and_not(b, m);
}

// The component of a named per lane by two masks: x, else y, else z.
template <class F>
inline F component(const Vec3<F>& a, const Mask<F>& is_x, const Mask<F>& is_y) {
  return select(is_x, a.x, select(is_y, a.y, a.z));
}

}  // namespace triangle_detail

struct TriangleMollerTrumbore : RayAsIs {
  template <class F>
  static Mask<F> intersect(const Ray<F>& ray, const TriangleLanes<F>& tri, const F& tmax,
                           const Mask<F>& active, Candidate<F>& out) {
    using namespace triangle_detail;
    const Vec3<F> e1 = tri.v1 - tri.v0;
    const Vec3<F> e2 = tri.v2 - tri.v0;
    // det = e1.(d x e2): zero when the ray is parallel to the plane.
    const Vec3<F> p = cross(ray.direction, e2);
    const F det = dot(e1, p);
    const Mask<F> crosses = det != F(0.f);
    const F inv_det = F(1.f) / select(crosses, det, F(1.f));
    // u from the origin's offset T projected on p.
    const Vec3<F> offset = ray.origin - tri.v0;
    const F u = dot(offset, p) * inv_det;
    // v from the direction projected on q = T x e1.
    const Vec3<F> q = cross(offset, e1);
    const F v = dot(ray.direction, q) * inv_det;
    const Mask<F> candidate = active && crosses && u >= F(0.f) && v >= F(0.f) && u + v <= F(1.f);
    if (none(candidate)) return no_hit(candidate, out);
    const F t = dot(e2, q) * inv_det;
    const Vec3<F> ng = cross(e1, e2);
    out.t = t;
    out.u = u;
    out.v = v;
    out.ng = ng;
    return candidate && t > ray.tmin && t < tmax && nonzero(ng);
  }
};

// A ray prepared for the watertight test: per-lane axis masks and shear.
template <class F>
struct WatertightRay {
  Vec3<F> origin;
  Mask<F> kx_is_x, kx_is_y, ky_is_x, ky_is_y, kz_is_x, kz_is_y;
  F sx, sy, sz;
  F tmin;
  Mask<F> valid;  // direction not zero
  Mask<F> swap;   // d[kz] < 0: kx and ky swapped
  // kz * 2 + swap when every lane shares them, else kMixedAxes.
  int shared_axes;
};

inline constexpr int kMixedAxes = -1;

// A packet's rays prepared for scans ray by ray (TriangleWatertight::
// prepare_lanes), stored per lane, with the lanes of each frame kz * 2 + swap.
template <class F>
struct WatertightLanes {
  static constexpr int kLanes = lane_count<F>;
  alignas(64) std::array<float, kLanes> origin_x, origin_y, origin_z, sx, sy, sz, tmin;
  unsigned valid = 0;
  std::array<unsigned, 6> frame_lanes{};
};

namespace triangle_detail {

// The sheared frame's axes chosen per lane by the ray's masks.
struct AxesPerLane {
  template <class F>
  static F x(const Vec3<F>& a, const WatertightRay<F>& r) { return component(a, r.kx_is_x, r.kx_is_y); }
  template <class F>
  static F y(const Vec3<F>& a, const WatertightRay<F>& r) { return component(a, r.ky_is_x, r.ky_is_y); }
  template <class F>
  static F z(const Vec3<F>& a, const WatertightRay<F>& r) { return component(a, r.kz_is_x, r.kz_is_y); }
};

// The same axes fixed for the packet: kz = KZ (0 x, 1 y, 2 z), kx and ky
// cyclic after it and swapped when Swap.
template <int KZ, bool Swap>
struct AxesFixed {
  static constexpr int kz = KZ;
  static constexpr int kx = Swap ? (KZ + 2) % 3 : (KZ + 1) % 3;
  static constexpr int ky = Swap ? (KZ + 1) % 3 : (KZ + 2) % 3;
  template <int K, class F>
  static const F& axis(const Vec3<F>& a) {
    if constexpr (K == 0) return a.x;
    else if constexpr (K == 1) return a.y;
    else return a.z;
  }
  template <class F>
  static F x(const Vec3<F>& a, const WatertightRay<F>&) { return axis<kx>(a); }
  template <class F>
  static F y(const Vec3<F>& a, const WatertightRay<F>&) { return axis<ky>(a); }
  template <class F>
  static F z(const Vec3<F>& a, const WatertightRay<F>&) { return axis<KZ>(a); }
};


// visit(Axes{}) in the ray's sheared frame: AxesFixed when every lane
// shares it, else AxesPerLane.
template <class F, class Visit>
[[gnu::always_inline]] inline decltype(auto) in_ray_frame(const WatertightRay<F>& r, const Visit& visit) {
  switch (r.shared_axes) {
    case 0: return visit(AxesFixed<0, false>{});
    case 1: return visit(AxesFixed<0, true>{});
    case 2: return visit(AxesFixed<1, false>{});
    case 3: return visit(AxesFixed<1, true>{});
    case 4: return visit(AxesFixed<2, false>{});
    case 5: return visit(AxesFixed<2, true>{});
    default: return visit(AxesPerLane{});
  }
}

}  // namespace triangle_detail

struct TriangleWatertight {
  template <class F>
  [[gnu::always_inline]] static WatertightRay<F> prepare(const Ray<F>& ray) {
    using namespace triangle_detail;
    const Vec3<F> d = ray.direction;
    const F ax = abs(d.x), ay = abs(d.y), az = abs(d.z);
    // kz = argmax |d|; ties go to z, then y.
    const Mask<F> z_is_z = az >= ax && az >= ay;
    const Mask<F> kz_is_y = !z_is_z && ay >= ax;
    const Mask<F> kz_is_x = !z_is_z && !kz_is_y;
    // kx, ky follow kz cyclically: z -> (x, y), x -> (y, z), y -> (z, x).
    const Mask<F> kx_is_x = z_is_z, kx_is_y = kz_is_x;
    const Mask<F> ky_is_x = kz_is_y, ky_is_y = z_is_z;
    const F dz = component(d, kz_is_x, kz_is_y);
    // Swap kx and ky when d[kz] < 0 to keep the winding.
    const Mask<F> swap = dz < F(0.f);
    WatertightRay<F> r;
    r.swap = swap;
    r.origin = ray.origin;
    r.kx_is_x = choose<F>(swap, ky_is_x, kx_is_x);
    r.kx_is_y = choose<F>(swap, ky_is_y, kx_is_y);
    r.ky_is_x = choose<F>(swap, kx_is_x, ky_is_x);
    r.ky_is_y = choose<F>(swap, kx_is_y, ky_is_y);
    r.kz_is_x = kz_is_x;
    r.kz_is_y = kz_is_y;
    // Shear: d[kz] is zero only for a zero direction; feed 1 there.
    r.valid = dz != F(0.f);
    const F safe_dz = select(r.valid, dz, F(1.f));
    r.sx = component(d, r.kx_is_x, r.kx_is_y) / safe_dz;
    r.sy = component(d, r.ky_is_x, r.ky_is_y) / safe_dz;
    r.sz = F(1.f) / safe_dz;
    r.tmin = ray.tmin;
    const int shared_kz = all(kz_is_x) ? 0 : all(kz_is_y) ? 1 : all(z_is_z) ? 2 : -1;
    const bool shared_swap = all(swap) || none(swap);
    r.shared_axes = shared_kz >= 0 && shared_swap ? shared_kz * 2 + (all(swap) ? 1 : 0) : kMixedAxes;
    return r;
  }

  // One ray prepared once and broadcast to F's lanes, for a scan over W
  // triangles at a time: calls visit(prepared, Axes{}) with the ray's frame
  // as a compile-time AxesFixed, so that a caller testing many blocks
  // (the single-ray BVH walk) chooses the frame once per ray, not per block.
  // The scalar ray is prepared and its fields broadcast, so the axis choice
  // runs once on floats instead of on every lane of a broadcast ray.
  template <class F, class Visit>
  [[gnu::always_inline]] static void with_fixed_axes(const Ray<float>& ray, Visit&& visit) {
    using namespace triangle_detail;
    const WatertightRay<float> one = prepare(ray);
    WatertightRay<F> r;
    r.origin = Vec3<F>(F(one.origin.x), F(one.origin.y), F(one.origin.z));
    r.kx_is_x = Mask<F>(one.kx_is_x);
    r.kx_is_y = Mask<F>(one.kx_is_y);
    r.ky_is_x = Mask<F>(one.ky_is_x);
    r.ky_is_y = Mask<F>(one.ky_is_y);
    r.kz_is_x = Mask<F>(one.kz_is_x);
    r.kz_is_y = Mask<F>(one.kz_is_y);
    r.sx = F(one.sx);
    r.sy = F(one.sy);
    r.sz = F(one.sz);
    r.tmin = F(one.tmin);
    r.valid = Mask<F>(one.valid);
    r.swap = Mask<F>(one.swap);
    r.shared_axes = one.shared_axes;  // one ray: never kMixedAxes
    switch (one.shared_axes) {
      case 0: return visit(r, AxesFixed<0, false>{});
      case 1: return visit(r, AxesFixed<0, true>{});
      case 2: return visit(r, AxesFixed<1, false>{});
      case 3: return visit(r, AxesFixed<1, true>{});
      case 4: return visit(r, AxesFixed<2, false>{});
      default: return visit(r, AxesFixed<2, true>{});
    }
  }

  // A packet's rays prepared at once for scans ray by ray: prepare on the
  // packet's lanes does per lane what with_fixed_axes does for one ray, so
  // each lane's values are the same bits, without one ray's divisions and
  // frame branches.
  template <class F>
  [[gnu::always_inline]] static WatertightLanes<F> prepare_lanes(const Ray<F>& ray) {
    const WatertightRay<F> r = prepare(ray);
    WatertightLanes<F> lanes;
    store_lanes(r.origin.x, lanes.origin_x.data());
    store_lanes(r.origin.y, lanes.origin_y.data());
    store_lanes(r.origin.z, lanes.origin_z.data());
    store_lanes(r.sx, lanes.sx.data());
    store_lanes(r.sy, lanes.sy.data());
    store_lanes(r.sz, lanes.sz.data());
    store_lanes(r.tmin, lanes.tmin.data());
    lanes.valid = lane_bits(r.valid);
    const unsigned kz_x = lane_bits(r.kz_is_x), kz_y = lane_bits(r.kz_is_y), swapped = lane_bits(r.swap);
    const unsigned kz_z = ~(kz_x | kz_y);
    lanes.frame_lanes = {kz_x & ~swapped, kz_x & swapped, kz_y & ~swapped, kz_y & swapped, kz_z & ~swapped,
                         kz_z & swapped};
    return lanes;
  }

  // Calls visit(lane, prepared, Axes{}) for each lane in `lanes`, frame by
  // frame (the lanes of one frame in a row): prepared is the lane's ray
  // broadcast to G, as with_fixed_axes hands it over.
  template <class G, class F, class Visit>
  [[gnu::always_inline]] static void for_each_lane_by_frame(const WatertightLanes<F>& prepared, unsigned lanes,
                                                           const Visit& visit) {
    using namespace triangle_detail;
    for (int frame = 0; frame < 6; ++frame) {
      const unsigned in_frame = lanes & prepared.frame_lanes[static_cast<std::size_t>(frame)];
      if (in_frame == 0) continue;
      switch (frame) {
        case 0: visit_lanes<AxesFixed<0, false>, G>(prepared, in_frame, frame, visit); break;
        case 1: visit_lanes<AxesFixed<0, true>, G>(prepared, in_frame, frame, visit); break;
        case 2: visit_lanes<AxesFixed<1, false>, G>(prepared, in_frame, frame, visit); break;
        case 3: visit_lanes<AxesFixed<1, true>, G>(prepared, in_frame, frame, visit); break;
        case 4: visit_lanes<AxesFixed<2, false>, G>(prepared, in_frame, frame, visit); break;
        default: visit_lanes<AxesFixed<2, true>, G>(prepared, in_frame, frame, visit); break;
      }
    }
  }

  template <class F>
  static Mask<F> intersect(const WatertightRay<F>& ray, const TriangleLanes<F>& tri, const F& tmax,
                           const Mask<F>& active, Candidate<F>& out) {
    using namespace triangle_detail;
    return in_ray_frame(ray, [&](auto axes) __attribute__((always_inline)) {
      return intersect_in<decltype(axes)>(ray, tri, tmax, active, out);
    });
  }

  // for_each_lane_by_frame's lanes of one frame.
  template <class Axes, class G, class F, class Visit>
  [[gnu::always_inline]] static void visit_lanes(const WatertightLanes<F>& prepared, unsigned lanes, int frame,
                                                 const Visit& visit) {
    for (; lanes != 0; lanes &= lanes - 1) {
      const int lane = __builtin_ctz(lanes);
      const std::size_t k = static_cast<std::size_t>(lane);
      WatertightRay<G> r;
      r.origin = Vec3<G>(G(prepared.origin_x[k]), G(prepared.origin_y[k]), G(prepared.origin_z[k]));
      r.sx = G(prepared.sx[k]);
      r.sy = G(prepared.sy[k]);
      r.sz = G(prepared.sz[k]);
      r.tmin = G(prepared.tmin[k]);
      r.kx_is_x = Mask<G>(Axes::kx == 0);
      r.kx_is_y = Mask<G>(Axes::kx == 1);
      r.ky_is_x = Mask<G>(Axes::ky == 0);
      r.ky_is_y = Mask<G>(Axes::ky == 1);
      r.kz_is_x = Mask<G>(Axes::kz == 0);
      r.kz_is_y = Mask<G>(Axes::kz == 1);
      r.valid = Mask<G>(((prepared.valid >> lane) & 1u) != 0);
      r.swap = Mask<G>((frame & 1) != 0);
      r.shared_axes = frame;
      visit(lane, r, Axes{});
    }
  }

  // The test in the frame Axes picks (see AxesPerLane, AxesFixed).
  template <class Axes, class F>
  static Mask<F> intersect_in(const WatertightRay<F>& ray, const TriangleLanes<F>& tri, const F& tmax,
                              const Mask<F>& active, Candidate<F>& out) {
    using namespace triangle_detail;
    // Vertices relative to the origin, permuted so the ray runs along kz.
    const Vec3<F> a = tri.v0 - ray.origin, b = tri.v1 - ray.origin, c = tri.v2 - ray.origin;
    const F az = Axes::z(a, ray);
    const F bz = Axes::z(b, ray);
    const F cz = Axes::z(c, ray);
    // Shear x, y so the ray is the z axis of the 2D edge tests (fused: one
    // rounding per coordinate; the paper's unfused form missed more far away).
    const F ax = fma(-ray.sx, az, Axes::x(a, ray));
    const F ay = fma(-ray.sy, az, Axes::y(a, ray));
    const F bx = fma(-ray.sx, bz, Axes::x(b, ray));
    const F by = fma(-ray.sy, bz, Axes::y(b, ray));
    const F cx = fma(-ray.sx, cz, Axes::x(c, ray));
    const F cy = fma(-ray.sy, cz, Axes::y(c, ray));
    // Edge functions, unfused so a shared edge gives exactly opposite values.
    F w0 = cx * by - cy * bx;
    F w1 = ax * cy - ay * cx;
    F w2 = bx * ay - by * ax;
    // A zero may be rounding: recompute it with one rounding for its sign.
    const Mask<F> w0_zero = w0 == F(0.f), w1_zero = w1 == F(0.f), w2_zero = w2 == F(0.f);
    if (any(w0_zero || w1_zero || w2_zero)) {
      w0 = select(w0_zero, difference_of_products(cx, by, cy, bx), w0);
      w1 = select(w1_zero, difference_of_products(ax, cy, ay, cx), w1);
      w2 = select(w2_zero, difference_of_products(bx, ay, by, ax), w2);
    }
    const Mask<F> inside = (w0 >= F(0.f) && w1 >= F(0.f) && w2 >= F(0.f)) ||
                           (w0 <= F(0.f) && w1 <= F(0.f) && w2 <= F(0.f));
    const F det = w0 + w1 + w2;
    const Mask<F> crosses = det != F(0.f);
    const Mask<F> candidate = active && ray.valid && inside && crosses;
    if (none(candidate)) return no_hit(candidate, out);
    // Scaled distance, divided only now that some lane is inside.
    const F scaled_t = w0 * (ray.sz * az) + w1 * (ray.sz * bz) + w2 * (ray.sz * cz);
    const F inv_det = F(1.f) / select(crosses, det, F(1.f));
    const F t = scaled_t * inv_det;
    const Mask<F> in_range = candidate && t > ray.tmin && t < tmax;
    if (none(in_range)) return no_hit(in_range, out);
    const Vec3<F> ng = cross(tri.v1 - tri.v0, tri.v2 - tri.v0);
    out.t = t;
    out.u = w1 * inv_det;
    out.v = w2 * inv_det;
    out.ng = ng;
    return in_range && nonzero(ng);
  }
};

// The product's triangle test: fn(kernel) for watertight (Moller-Trumbore
// is the study's: tests/support/study_streams.h).
template <class Fn>
inline auto with_product_method(TriangleMethod method, Fn fn) {
  switch (method) {
    case TriangleMethod::watertight: return fn(TriangleWatertight{});
    case TriangleMethod::moller_trumbore: break;
  }
  throw_study_method("triangle", "moller_trumbore");
}

}  // namespace QUIVER_UNIT_NAMESPACE

struct TriangleDesc {
  std::array<Vec3<float>, 3> p;
  std::optional<std::array<Vec3<float>, 3>> normals;         // per vertex, any length
  std::optional<std::array<std::array<float, 2>, 3>> uvs;    // per vertex (u, v)
};

struct TriangleSoA {
  AlignedFloats v0x, v0y, v0z, v1x, v1y, v1z, v2x, v2y, v2z;
  AlignedFloats n0x, n0y, n0z, n1x, n1y, n1z, n2x, n2y, n2z;  // unit, or empty
  AlignedFloats uv0u, uv0v, uv1u, uv1v, uv2u, uv2v;            // or empty
  std::size_t count = 0;
  // Input index of each kept primitive (builders drop some), and the id of
  // primitive 0 in hits (a scene numbers its stores consecutively).
  std::vector<std::uint32_t> source;
  std::int32_t id_base = 0;

  // BVH traversal: incoherent packets go ray by ray (geometry/bvh/bvh_streams.h).
  static constexpr bool kIncoherentRaysTraverseAlone = true;
  // columns() hold every per-primitive field: a BVH reorders the store by
  // gathering them (geometry/bvh_store.h).
  static constexpr bool kColumnsHoldEveryField = true;

  std::size_t size() const { return count; }
  bool has_normals() const { return !n0x.empty(); }
  bool has_uvs() const { return !uv0u.empty(); }

  template <class F>
  TriangleLanes<F> broadcast(std::size_t i) const {
    return {broadcast_vec3<F>(v0x, v0y, v0z, i), broadcast_vec3<F>(v1x, v1y, v1z, i),
            broadcast_vec3<F>(v2x, v2y, v2z, i)};
  }
  template <class F>
  TriangleLanes<F> load(std::size_t first) const {
    return {load_vec3_unaligned<F>(v0x, v0y, v0z, first), load_vec3_unaligned<F>(v1x, v1y, v1z, first),
            load_vec3_unaligned<F>(v2x, v2y, v2z, first)};
  }
  // Vertex k (0, 1, 2) of triangle i.
  Vec3<float> vertex(std::size_t i, int k) const;
  // Shading normal at vertex k; requires has_normals().
  Vec3<float> normal(std::size_t i, int k) const;
  // Texture coordinates at vertex k; requires has_uvs().
  std::array<float, 2> uv(std::size_t i, int k) const;
  // Every column, for padding and checks (the optional ones may be empty).
  template <class Self>
  static auto columns_of(Self& s) {
    return std::array{&s.v0x,  &s.v0y,  &s.v0z,  &s.v1x,  &s.v1y,  &s.v1z,  &s.v2x,  &s.v2y,
                      &s.v2z,  &s.n0x,  &s.n0y,  &s.n0z,  &s.n1x,  &s.n1y,  &s.n1z,  &s.n2x,
                      &s.n2y,  &s.n2z,  &s.uv0u, &s.uv0v, &s.uv1u, &s.uv1v, &s.uv2u, &s.uv2v};
  }
  auto columns() { return columns_of(*this); }
  auto columns() const { return columns_of(*this); }
  std::size_t memory_bytes() const;  // columns and source list
};

// Smallest height / longest edge a kept triangle may have: below half a float
// ulp of the longest edge a triangle is a segment for a float kernel.
inline constexpr double kMinTriangleRelativeHeight = 0x1p-24;

// Drops triangles with a non-finite number (vertex, normal, uv, or an edge or
// normal that overflows) and degenerate ones: zero area (repeated vertex,
// collinear vertices), height below kMinTriangleRelativeHeight times the
// longest edge (computed in double), or a float edge cross product that is
// exactly zero. When some triangles have normals (uvs) and others do not,
// the others get the unit geometric normal (uvs (0,0), (1,0), (0,1)); a zero
// shading normal is replaced by the geometric one; normals are normalised.
TriangleSoA build_triangles(const DescRefs<TriangleDesc>& triangles, BuildReport& report);

// Triangles of an indexed mesh, in index order, without normals or uvs.
// Throws std::out_of_range for an index past positions.
std::vector<TriangleDesc> triangles_from_indexed(std::span<const Vec3<float>> positions,
                                                 std::span<const std::array<std::uint32_t, 3>> indices);

// A conservative axis-aligned box of primitive i as stored (geometry/primitive_bounds.h).
Box primitive_box(const TriangleSoA& store, std::size_t i);

// Its surface at a hit (geometry/surface_mapping.h).
void map_surface(const TriangleSoA& store, const MappingQuery& query, SurfaceMapping& out);

// The triangle in the scene's list of kinds (geometry/kinds.h).
struct TriangleKind {
  static constexpr std::string_view name = "triangle", plural = "triangles";
  static constexpr bool bounded = true;
  using Method = TriangleMethod;
  static constexpr TriangleMethod product_method = TriangleMethod::watertight;
  using Desc = TriangleDesc;
  using Store = TriangleSoA;
  static Store build(const DescRefs<Desc>& descs, BuildReport& report) { return build_triangles(descs, report); }
  // add(point, margin) for points and margins whose boxes hold the described surface.
  template <class Add>
  static void extent(const Desc& d, Add add) {
    for (const Vec3<float>& p : d.p) add(p, 0.0);
  }
};

}  // namespace quiver
