// Ray / infinite plane, two formulas for t over one stored plane (unit n,
// a point p on it as given, and d = -n.p rounded to float):
//   seed:     t = -(d + n.o) / (n.dir), the seed's formula. d + n.o cancels
//             when the origin is far from the world origin, so t's absolute
//             error is about eps (|d| + |o|) / |n.dir|, however short t is.
//   anchored: t = n.(p - o) / (n.dir). p - o is exact or nearly so when o is
//             near p, so the error follows the ray's distance from the
//             plane's point, not from the world origin (as the robust
//             sphere's o - c).
// t-range: hit iff tmin < t < tmax. A ray parallel to the plane (n.dir == 0)
// misses, even when its origin lies on the plane; the division is then fed
// 1 so no lane makes a NaN or a division by zero.
// Masks: only active lanes can hit. u = v = 0 (planar texture coordinates
// come from the hit point at shading); ng = n (both sides hit).
//
// Infinite planes in SoA: unit normal (nx, ny, nz), offset d = -n.p in
// float (the seed's formula) and the point p as given (px, py, pz).
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

enum class PlaneMethod { seed, anchored };

inline namespace QUIVER_UNIT_NAMESPACE {

template <class F>
struct PlaneLanes {
  Vec3<F> normal;  // unit length
  F d;             // n.P + d = 0 on the plane
  Vec3<F> point;   // on the plane, as given
};

// t = numer / (n.dir); `crosses` marks the lanes not parallel to the plane
// (the others divide by 1 and must be masked off).
template <class F>
inline F divide_by_slope(const F& numer, const Ray<F>& ray, const Vec3<F>& normal, Mask<F>& crosses) {
  const F denom = dot(normal, ray.direction);
  crosses = denom != F(0.f);
  return numer / select(crosses, denom, F(1.f));
}

// t where the ray meets the plane n.P + d = 0 (the seed's formula).
template <class F>
inline F plane_crossing(const Ray<F>& ray, const Vec3<F>& normal, const F& d, Mask<F>& crosses) {
  return divide_by_slope(-(d + dot(normal, ray.origin)), ray, normal, crosses);
}

// The candidate of a plane hit at t: both sides, no surface coordinates.
template <class F>
inline Mask<F> plane_candidate(const Ray<F>& ray, const PlaneLanes<F>& plane, const F& t, const Mask<F>& crosses,
                               const F& tmax, const Mask<F>& active, Candidate<F>& out) {
  out.t = t;
  out.u = F(0.f);
  out.v = F(0.f);
  out.ng = plane.normal;
  return active && crosses && out.t > ray.tmin && out.t < tmax;
}

struct PlaneSeed : RayAsIs {
  template <class F>
  static Mask<F> intersect(const Ray<F>& ray, const PlaneLanes<F>& plane, const F& tmax,
                           const Mask<F>& active, Candidate<F>& out) {
    Mask<F> crosses;
    const F t = plane_crossing(ray, plane.normal, plane.d, crosses);
    return plane_candidate(ray, plane, t, crosses, tmax, active, out);
  }
};

struct PlaneAnchored : RayAsIs {
  template <class F>
  static Mask<F> intersect(const Ray<F>& ray, const PlaneLanes<F>& plane, const F& tmax,
                           const Mask<F>& active, Candidate<F>& out) {
    Mask<F> crosses;
    const F t = divide_by_slope(dot(plane.normal, plane.point - ray.origin), ray, plane.normal, crosses);
    return plane_candidate(ray, plane, t, crosses, tmax, active, out);
  }
};

// The product's plane test: fn(kernel) for anchored (the seed's is the
// study's: tests/support/study_streams.h).
template <class Fn>
inline auto with_product_method(PlaneMethod method, Fn fn) {
  switch (method) {
    case PlaneMethod::anchored: return fn(PlaneAnchored{});
    case PlaneMethod::seed: break;
  }
  throw_study_method("plane", "seed");
}

}  // namespace QUIVER_UNIT_NAMESPACE

// A plane through `point` with normal `normal` (any non-zero length).
struct PlaneDesc {
  Vec3<float> point;
  Vec3<float> normal;
};

struct PlaneSoA {
  AlignedFloats nx, ny, nz, d, px, py, pz;
  std::size_t count = 0;
  // Input index of each kept primitive (builders drop some), and the id of
  // primitive 0 in hits (a scene numbers its stores consecutively).
  std::vector<std::uint32_t> source;
  std::int32_t id_base = 0;

  std::size_t size() const { return count; }
  // Every column, the one list of them (const for memory reports).
  template <class Self>
  static auto columns_of(Self& s) { return std::array{&s.nx, &s.ny, &s.nz, &s.d, &s.px, &s.py, &s.pz}; }
  auto columns() { return columns_of(*this); }
  auto columns() const { return columns_of(*this); }
  // Bytes held by the columns and the source list.
  std::size_t memory_bytes() const;
  template <class F>
  PlaneLanes<F> broadcast(std::size_t i) const {
    return {broadcast_vec3<F>(nx, ny, nz, i), F(d[i]), broadcast_vec3<F>(px, py, pz, i)};
  }
  template <class F>
  PlaneLanes<F> load(std::size_t first) const {
    return {load_vec3_unaligned<F>(nx, ny, nz, first), load_lanes_unaligned<F>(d.data() + first),
            load_vec3_unaligned<F>(px, py, pz, first)};
  }
};

// Drops planes with a non-finite number or a zero (or underflowing) normal.
PlaneSoA build_planes(const DescRefs<PlaneDesc>& planes, BuildReport& report);

// Its surface at a hit (geometry/surface_mapping.h).
void map_surface(const PlaneSoA& store, const MappingQuery& query, SurfaceMapping& out);

// The plane in the scene's list of kinds (geometry/kinds.h): unbounded, so
// scanned, never in a BVH.
struct PlaneKind {
  static constexpr std::string_view name = "plane", plural = "planes";
  static constexpr bool bounded = false;
  using Method = PlaneMethod;
  static constexpr PlaneMethod product_method = PlaneMethod::anchored;
  using Desc = PlaneDesc;
  using Store = PlaneSoA;
  static Store build(const DescRefs<Desc>& descs, BuildReport& report) { return build_planes(descs, report); }
  // add(point, margin) for points and margins whose boxes hold the described
  // surface: the plane's point (the plane itself has no box).
  template <class Add>
  static void extent(const Desc& d, Add add) {
    add(d.point, 0.0);
  }
};

}  // namespace quiver
