// Ray / planar polygon (n >= 3 vertices, convex or concave), watertight
// across polygons that share edges (closed polygon meshes):
//   1. plane hit, anchored at the first vertex V0 as stored: t = n.(V0 - o)
//      / (n.dir) with unit n (divide_by_slope, geometry/plane.h, as
//      PlaneAnchored), so t keeps its digits far from the world origin
//      (V0 - o is exact or nearly so near the polygon, where d + n.o with a
//      float d = -n.C would cancel); the hit point projected onto the
//      polygon's dominant plane (drop the axis k of n's largest |component|,
//      chosen at build time): (u, v) = (P[(k+1)%3], P[(k+2)%3]) relative to
//      the first vertex;
//   2. lanes clear of every edge are decided in that projection: outside the
//      2D bounding rectangle, or by an edge band (below); "clear" by
//      each lane's margin, a bound on how far rounding (and t's plane's
//      distance from the vertices) moves the projected hit point
//      from the ray's true crossing: 2^-16 * (|t| |d|_1 + |o|_1 + reach) +
//      2 * plane_slack, times |d|_1 / |n.d| (reach: the largest |V|_1 + |d|
//      with d = -n.C through the centroid; plane_slack: the largest
//      |n.(V - V0)| over the vertices). To first
//      order, rounding moves the projected hit point by 7 ulp of that sum
//      times |d|_1 / |n.d|, and the shear below moves the vertices by what
//      looks like 17 ulp of it on the plane: the 2^-16 is 10 times more;
//   3. every other lane (near an edge or a vertex) is decided in ray space,
//      as the watertight triangle test (Woop, Benthin & Wald, "Watertight
//      Ray/Triangle Intersection", JCGT 2(1), 2013; TriangleWatertight::
//      prepare gives kz, kx, ky and the shear Sx, Sy): each 3D vertex is
//      translated by the ray origin and sheared, x = fma(-Sx, V'[kz],
//      V'[kx]), y = fma(-Sy, V'[kz], V'[ky]), so the ray is the point
//      (0, 0); the crossing (even-odd) test counts the edges the 2D ray from
//      (0, 0) along +x crosses (Haines, "Point in Polygon Strategies",
//      Graphics Gems IV, 1994). Edge (a, b) straddles iff (a.y > 0) !=
//      (b.y > 0) (half-open, so a vertex on the line counts once or not at
//      all), and crosses on +x iff lo.x hi.y - lo.y hi.x > 0 with lo, hi its
//      ends below and above: unfused products (the plain float value has
//      the exact sign or is 0), an exact 0 recomputed with
//      difference_of_products (the exact sign unless the products
//      underflow), a true 0 (the ray through the edge) not counted. The
//      decision depends on the edge's two vertices and the ray only, not on
//      its direction or its polygon, so two polygons sharing an edge decide
//      it alike and a ray near it is inside exactly one of them (or, where
//      the edge is a silhouette, both or neither).
// Edge bands (polygons of many vertices, see PolygonSoA): the v range is cut
// into bands, each listing the edges whose v range meets it. A lane whose
// v +- margin stays in one band has every edge within its margin in that
// list. The band's span (BandSpan) decides it without edges if u is beyond
// a bound by the margin: left or right of all its edges' u ranges is
// outside, within its widest gap between them of odd parity inside (each
// bound kBandSpanMargin of the rectangle's width from every edge). Else the
// crossing test in the projection over the band's edges decides it if it is
// clear of each by its margin (band_parity); the others go to the ray-space
// test over every edge.
// All lanes share the polygon, so the edge loop is the same for every lane;
// an edge no lane straddles is skipped (it could toggle no lane).
// t-range: hit iff tmin < t < tmax. A ray parallel to the plane (n.dir == 0)
// misses, even in the plane; its division is fed 1 (no NaN, no division by 0).
// Masks: only active lanes can hit; early exit only when no lane is left.
// Output: ng = the unit plane normal (Newell's method; counter-clockwise
// vertex order seen from where ng points); u, v = the hit point's projected
// 2D coordinates relative to the first vertex, (P - V0)[(k+1)%3] and
// (P - V0)[(k+2)%3] (not normalised; for k = 2 they are x and y).
//
// Planar polygons in SoA: per polygon the unit plane normal (nx, ny, nz), the kept
// axes of the dominant projection, the first vertex projected, the 2D bounding
// rectangle, the lane margin's reach and plane slack (see the kernel above) and
// the vertex range; the vertices live in flat columns, projected relative to
// each polygon's first vertex (pu, pv) and in 3D as given (px, py, pz: the
// ray-space test reads them, so two polygons sharing a vertex read the same
// floats). Packets only: broadcast<F>(i) hands every lane the same polygon.
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
#include "geometry/kinds/plane.h"
#include "geometry/kinds/triangle.h"
#include "geometry/method_error.h"
#include "geometry/surface_mapping.h"
#include "geometry/soa.h"
#include "simd/ray.h"

namespace quiver {

enum class PolygonMethod { crossing };

// Per band: u < edges_lo or u > edges_hi: outside (left or right of every
// edge the band lists); inside_lo < u < inside_hi: inside (an empty range
// when no gap qualifies). Relative coordinates, as the vertices.
struct BandSpan {
  float edges_lo, inside_lo, inside_hi, edges_hi;
};

inline namespace QUIVER_UNIT_NAMESPACE {

// A span bound's distance from the band's edge u ranges, relative to the
// polygon's rectangle width.
inline constexpr float kBandSpanMargin = 0x1p-18f;
// The lane margin's rounding factor (step 2 of the header).
inline constexpr float kPolygonLaneMargin = 0x1p-16f;

template <class F>
struct PolygonLanes {
  Vec3<F> normal;          // unit length
  Vec3<F> anchor;          // the first vertex in 3D, as given: t's plane passes through it
  int axis_u, axis_v;      // the kept axes, (k+1)%3 and (k+2)%3
  F origin_u, origin_v;    // the first vertex, projected
  F umin, umax, vmin, vmax;  // bounding rectangle, relative to the first vertex
  F reach, plane_slack;    // of the lane margin (step 2 of the header)
  const float* pu;         // vertex_count projected vertices relative to the first
  const float* pv;
  const float* px;         // the same vertices in 3D (as given)
  const float* py;
  const float* pz;
  int vertex_count;
  // Edge bands: band_count 0 (none) or >= 2 bands over [band_vmin, vmax];
  // band b lists band_edges[band_first[b] .. band_first[b + 1]), edge k
  // joining vertex k - 1 (cyclic) to vertex k.
  int band_count;
  float band_vmin, band_scale;
  const std::size_t* band_first;
  const std::uint32_t* band_edges;
  const BandSpan* band_spans;  // band b's span at band_spans[b]
};

// The ray and its watertight frame (kz, kx, ky, shear), prepared per packet,
// and the sums the lane margin needs.
template <class F>
struct PolygonRay {
  Ray<F> ray;
  WatertightRay<F> sheared;
  F direction_sum;  // |d|_1
  F origin_sum;     // |o|_1
};

namespace polygon_detail {

// v's position in band units (relative coordinates as stored), per lane.
template <class F>
inline F band_position(const F& v, float vmin, float scale) {
  return (v - F(vmin)) * F(scale);
}

// The band at position x >= 0: band b holds [b, b + 1), the last one the rest.
inline int band_at(float x, int count) {
  return x < static_cast<float>(count - 1) ? static_cast<int>(x) : count - 1;
}

// The band of v (vmin <= v): non-decreasing in v, so an edge whose v range
// is [v0, v1] meets exactly the bands band_of(v0) .. band_of(v1). The
// builder and the kernel both use it.
inline int band_of(float v, float vmin, float scale, int count) {
  return band_at(band_position(v, vmin, scale), count);
}

// Vertex k in the ray's sheared frame (Axes: geometry/triangle.h).
template <class Axes, class F>
[[gnu::always_inline]] inline void sheared_vertex(const WatertightRay<F>& r, const PolygonLanes<F>& poly, int k, F& x,
                                                  F& y) {
  const Vec3<F> p = Vec3<F>(F(poly.px[k]), F(poly.py[k]), F(poly.pz[k])) - r.origin;
  const F z = Axes::z(p, r);
  x = fma(-r.sx, z, Axes::x(p, r));
  y = fma(-r.sy, z, Axes::y(p, r));
}

// The lanes of `lanes` inside the polygon by the ray-space crossing test
// (step 3 of the header), over edges (a, b) = (vertex k - 1, vertex k).
template <class Axes, class F>
inline Mask<F> ray_space_inside(const WatertightRay<F>& r, const PolygonLanes<F>& poly, const Mask<F>& lanes) {
  const int n = poly.vertex_count;
  F ax, ay;
  sheared_vertex<Axes>(r, poly, n - 1, ax, ay);
  Mask<F> a_above = ay > F(0.f);
  Mask<F> inside(false);
  for (int k = 0; k < n; ++k) {
    F bx, by;
    sheared_vertex<Axes>(r, poly, k, bx, by);
    const Mask<F> b_above = by > F(0.f);
    const Mask<F> straddles = masks_differ(a_above, b_above) && lanes;
    if (any(straddles)) {
      // lo.x hi.y - lo.y hi.x: a.x b.y - a.y b.x when b is above, its exact negation when below.
      const F e = ax * by - ay * bx;
      F side = select(b_above, e, -e);
      const Mask<F> zero = side == F(0.f) && straddles;
      if (any(zero)) {
        const F lo_x = select(b_above, ax, bx), lo_y = select(b_above, ay, by);
        const F hi_x = select(b_above, bx, ax), hi_y = select(b_above, by, ay);
        side = select(zero, difference_of_products(lo_x, hi_y, lo_y, hi_x), side);
      }
      inside = masks_differ(inside, straddles && side > F(0.f));
    }
    ax = bx;
    ay = by;
    a_above = b_above;
  }
  return inside;
}

// ray_space_inside in the ray's frame: fixed when every lane shares it.
template <class F>
inline Mask<F> ray_space_inside(const WatertightRay<F>& r, const PolygonLanes<F>& poly, const Mask<F>& lanes) {
  return triangle_detail::in_ray_frame(
      r, [&](auto axes) { return ray_space_inside<decltype(axes)>(r, poly, lanes); });
}

// The parity of the lanes in `lanes` over the edges of one band, in the
// projection; `clear` gets the lanes farther than their margin from every
// one of those edges (outside the edge's box grown by the margin, or
// |side| > 2 margin |edge|_1, so the distance to the line exceeds
// sqrt(2) margin), the others may be decided wrongly.
template <class F>
inline Mask<F> band_parity(const PolygonLanes<F>& poly, int band, const F& u, const F& v, const F& margin,
                           const Mask<F>& lanes, Mask<F>& clear) {
  const int n = poly.vertex_count;
  Mask<F> inside(false), near(false);
  for (std::size_t e = poly.band_first[band]; e < poly.band_first[band + 1]; ++e) {
    const int k = static_cast<int>(poly.band_edges[e]);
    const int j = k == 0 ? n - 1 : k - 1;
    const float au = poly.pu[j], av = poly.pv[j], bu = poly.pu[k], bv = poly.pv[k];
    const Mask<F> b_above = F(bv) > v;
    const Mask<F> straddles = masks_differ(F(av) > v, b_above) && lanes;
    // > 0 iff the point is left of a->b: the crossing lies on the +u side
    // iff the point is left of a->b when b is above, right of it when below.
    const F side = difference_of_products(v - F(av), F(bu - au), u - F(au), F(bv - av));
    inside = masks_differ(inside, and_not(straddles, masks_differ(side > F(0.f), b_above)));
    const Mask<F> in_box = u >= F(au < bu ? au : bu) - margin && u <= F(au < bu ? bu : au) + margin &&
                           v >= F(av < bv ? av : bv) - margin && v <= F(av < bv ? bv : av) + margin;
    const float length = (au < bu ? bu - au : au - bu) + (av < bv ? bv - av : av - bv);
    near = near || (in_box && abs(side) <= margin * F(2.f * length));
  }
  clear = and_not(lanes, near);
  return inside;
}

// The lanes of `lanes` (inside the bounding rectangle) decided without the
// ray-space test: those whose v +- margin stays in one band, then by the
// band's span if u is beyond its bound by the margin, else by the band's
// edges if clear of them (band_parity). `decided` marks them; the result is
// their inside mask. The open lanes of one band run together: those whose
// band position lies in [band, band + 1) (the last band: beyond).
template <class F>
inline Mask<F> banded_inside(const PolygonLanes<F>& poly, const F& u, const F& v, const F& margin,
                             const Mask<F>& lanes, Mask<F>& decided) {
  alignas(64) float u_lane[kMaxLanes], v_lane[kMaxLanes], margin_lane[kMaxLanes];
  store_lanes(u, u_lane);
  store_lanes(v, v_lane);
  store_lanes(margin, margin_lane);
  int lane_band[kMaxLanes];
  unsigned inside_bits = 0, known = 0, open = 0;
  for (unsigned b = lane_bits(lanes); b != 0; b &= b - 1) {
    const int lane = __builtin_ctz(b);
    const float lane_u = u_lane[lane], lane_v = v_lane[lane], m = margin_lane[lane];
    const float below = band_position(lane_v - m, poly.band_vmin, poly.band_scale);
    const float above = band_position(lane_v + m, poly.band_vmin, poly.band_scale);
    if (!(below >= 0.f)) continue;  // also a NaN margin
    const int band = band_at(below, poly.band_count);
    if (band_at(above, poly.band_count) != band) continue;
    lane_band[lane] = band;
    const BandSpan& span = poly.band_spans[band];
    const bool is_inside = lane_u > span.inside_lo + m && lane_u < span.inside_hi - m;
    const bool outside = lane_u < span.edges_lo - m || lane_u > span.edges_hi + m;
    inside_bits |= static_cast<unsigned>(is_inside) << lane;
    known |= static_cast<unsigned>(is_inside || outside) << lane;
    open |= static_cast<unsigned>(!is_inside && !outside) << lane;
  }
  Mask<F> inside = mask_from_bits<F>(inside_bits);
  decided = mask_from_bits<F>(known);
  if (open == 0) return inside;
  const Mask<F> open_lanes = mask_from_bits<F>(open);
  const F x = band_position(v, poly.band_vmin, poly.band_scale);
  const int last = poly.band_count - 1;
  for (unsigned pending = open; pending != 0;) {
    const int first = __builtin_ctz(pending);
    const int band = lane_band[first];
    const Mask<F> in_band = band < last ? x >= F(static_cast<float>(band)) && x < F(static_cast<float>(band + 1))
                                        : x >= F(static_cast<float>(last));
    const Mask<F> group = in_band && open_lanes;
    pending &= ~(lane_bits(group) | (1u << first));  // the first lane is in its group; cleared in any case
    Mask<F> clear;
    const Mask<F> parity = band_parity(poly, band, u, v, margin, group, clear);
    inside = inside || (parity && clear);
    decided = decided || clear;
  }
  return inside;
}

}  // namespace polygon_detail

struct PolygonCrossing {
  template <class F>
  [[gnu::always_inline]] static PolygonRay<F> prepare(const Ray<F>& ray) {
    const Vec3<F>& d = ray.direction;
    const Vec3<F>& o = ray.origin;
    return {ray, TriangleWatertight::prepare(ray), abs(d.x) + abs(d.y) + abs(d.z), abs(o.x) + abs(o.y) + abs(o.z)};
  }

  template <class F>
  static Mask<F> intersect(const PolygonRay<F>& prepared, const PolygonLanes<F>& poly, const F& tmax,
                           const Mask<F>& active, Candidate<F>& out) {
    const Ray<F>& ray = prepared.ray;
    Mask<F> crosses;
    out.t = divide_by_slope(dot(poly.normal, poly.anchor - ray.origin), ray, poly.normal, crosses);
    out.ng = poly.normal;
    // Projected hit point relative to the first vertex: (o - V0) + t dir.
    const F u = fma(out.t, ray.direction[poly.axis_u], ray.origin[poly.axis_u] - poly.origin_u);
    const F v = fma(out.t, ray.direction[poly.axis_v], ray.origin[poly.axis_v] - poly.origin_v);
    out.u = u;
    out.v = v;
    const Mask<F> in_range = active && crosses && out.t > ray.tmin && out.t < tmax;
    if (none(in_range)) return in_range;
    // The lane margin times |n.d| (step 2 of the header).
    const F cosine = abs(dot(poly.normal, ray.direction));
    const F reach = fma(abs(out.t), prepared.direction_sum, prepared.origin_sum + poly.reach);
    const F margin_cosine =
        prepared.direction_sum * fma(F(kPolygonLaneMargin), reach, poly.plane_slack + poly.plane_slack);
    // Bounding rectangle: lanes farther out than their margin miss.
    const F beyond = quiver::max(quiver::max(poly.umin - u, u - poly.umax), quiver::max(poly.vmin - v, v - poly.vmax));
    const Mask<F> candidate = in_range && beyond * cosine <= margin_cosine;
    if (none(candidate)) return candidate;
    Mask<F> inside(false), open = candidate;
    if (poly.band_count > 0) {
      const Mask<F> in_rectangle = candidate && beyond <= F(0.f);
      if (any(in_rectangle)) {
        const F margin = margin_cosine / select(in_rectangle, cosine, F(1.f));
        Mask<F> decided;
        inside = polygon_detail::banded_inside(poly, u, v, margin, in_rectangle, decided);
        open = and_not(candidate, decided);
        if (none(open)) return candidate && inside;
      }
    }
    inside = inside || polygon_detail::ray_space_inside(prepared.sheared, poly, open);
    return candidate && inside;
  }
};

// The polygon test: fn(kernel).
template <class Fn>
inline auto with_product_method(PolygonMethod method, Fn fn) {
  switch (method) {
    case PolygonMethod::crossing: break;
  }
  return fn(PolygonCrossing{});
}

}  // namespace QUIVER_UNIT_NAMESPACE

// Vertices in order (either winding; ng follows it counter-clockwise).
struct PolygonDesc {
  std::vector<Vec3<float>> vertices;
};
// Largest vertex count build_polygons accepts per polygon (more: degenerate).
inline constexpr std::size_t kMaxPolygonVertices = 1'000'000;

// Non-planar: some vertex lies farther than this times the polygon's extent
// (largest side of its 3D bounding box) from the fitted plane.
inline constexpr double kPolygonPlanarityTolerance = 1e-4;
// Zero area: |Newell normal| (twice the area) at most this times extent^2.
inline constexpr double kPolygonMinAreaRatio = 1e-10;
// Edge bands (geometry/polygon.h): polygons of at least this many vertices
// get min(kMaxEdgeBands, vertices / kEdgesPerBand) bands, halved while the
// band lists would hold more than kMaxBandRefsPerEdge entries per edge.
inline constexpr std::size_t kMinBandedVertices = 32;
inline constexpr std::size_t kEdgesPerBand = 8;
inline constexpr std::size_t kMaxEdgeBands = 64;
inline constexpr std::size_t kMaxBandRefsPerEdge = 4;

struct PolygonSoA {
  // Per polygon, padded to kMaxLanes like every SoA column.
  AlignedFloats nx, ny, nz;
  AlignedFloats origin_u, origin_v;
  AlignedFloats umin, umax, vmin, vmax;
  AlignedFloats reach, plane_slack;
  AlignedInts axis_u, axis_v, vertex_count;
  std::vector<std::size_t> first_vertex;
  // Per vertex, all polygons back to back.
  AlignedFloats pu, pv;
  AlignedFloats px, py, pz;
  // Edge bands, per polygon: band_count (0: none), the scale of band_of
  // (geometry/polygon.h), and where its band_count + 1 offsets into
  // band_edges start in band_first. band_spans runs beside band_first: the
  // span of the band each offset starts (a polygon's last offset starts
  // none; its span is empty).
  AlignedInts band_count;
  AlignedFloats band_scale;
  std::vector<std::size_t> band_start;
  std::vector<std::size_t> band_first;
  std::vector<std::uint32_t> band_edges;
  std::vector<BandSpan> band_spans;
  std::size_t count = 0;
  // Input index of each kept primitive (builders drop some), and the id of
  // primitive 0 in hits (a scene numbers its stores consecutively).
  std::vector<std::uint32_t> source;
  std::int32_t id_base = 0;

  std::size_t size() const { return count; }
  template <class F>
  PolygonLanes<F> broadcast(std::size_t i) const {
    return {broadcast_vec3<F>(nx, ny, nz, i),
            broadcast_vec3<F>(px, py, pz, first_vertex[i]),
            axis_u[i],
            axis_v[i],
            F(origin_u[i]),
            F(origin_v[i]),
            F(umin[i]),
            F(umax[i]),
            F(vmin[i]),
            F(vmax[i]),
            F(reach[i]),
            F(plane_slack[i]),
            pu.data() + first_vertex[i],
            pv.data() + first_vertex[i],
            px.data() + first_vertex[i],
            py.data() + first_vertex[i],
            pz.data() + first_vertex[i],
            vertex_count[i],
            band_count[i],
            vmin[i],
            band_scale[i],
            band_first.data() + band_start[i],
            band_edges.data(),
            band_spans.data() + band_start[i]};
  }
  // Bytes of every column and list.
  std::size_t memory_bytes() const;
  // The per-polygon columns (padded) and the per-vertex ones, the one list
  // of each (const for memory reports).
  template <class Self>
  static auto polygon_columns_of(Self& s) {
    return std::array{&s.nx,   &s.ny,   &s.nz,   &s.origin_u, &s.origin_v,    &s.umin,
                      &s.umax, &s.vmin, &s.vmax, &s.reach,    &s.plane_slack, &s.band_scale};
  }
  auto polygon_columns() { return polygon_columns_of(*this); }
  auto polygon_columns() const { return polygon_columns_of(*this); }
  template <class Self>
  static auto polygon_int_columns_of(Self& s) { return std::array{&s.axis_u, &s.axis_v, &s.vertex_count, &s.band_count}; }
  auto polygon_int_columns() { return polygon_int_columns_of(*this); }
  auto polygon_int_columns() const { return polygon_int_columns_of(*this); }
  auto vertex_columns() const { return std::array{&pu, &pv, &px, &py, &pz}; }
};

// Drops (with counts): a non-finite coordinate (also one whose projection
// overflows) as non-finite; more than kMaxPolygonVertices input vertices,
// fewer than 3 after removing consecutive duplicates (cyclically, in 3D;
// fewer than 3 distinct projected vertices too), zero area or a non-planar
// polygon (see the tolerances above) as degenerate. Vertices that differ
// in 3D are all kept, even where their projections coincide (a zero-length
// projected edge crosses nothing), so a vertex shared by two polygons is
// in both.
// Newell's normal of a closed polygon in double: twice its area vector,
// from the vertices relative to the first (no cancellation far from the
// origin); the counter-clockwise winding's side.
Vec3<double> newell_normal(std::span<const Vec3<float>> vertices);

PolygonSoA build_polygons(const DescRefs<PolygonDesc>& polygons, BuildReport& report);

// Ear-clipping triangulation of a simple (possibly concave) polygon, in its
// dominant projection, keeping the vertex winding. Consecutive duplicates are
// removed first; collinear vertices are clipped without a triangle. Empty for
// input build_polygons would drop. A polygon that is not simple still gives
// n - 2 triangles or fewer, but they need not cover it.
std::vector<std::array<Vec3<float>, 3>> triangulate_polygon(const PolygonDesc& polygon);

// A polygon of three vertices (after removing consecutive duplicates) as a
// triangle, with the polygon kernel's texture coordinates at its corners
// (each projected on the dominant plane, relative to the first vertex: the
// hit's u, v above). Nothing for a polygon of more vertices (quads
// included: a quad walks faster than its two triangles) or one
// build_polygons would drop (it reports those).
struct PolygonTriangle {
  std::array<Vec3<float>, 3> p;
  std::array<std::array<float, 2>, 3> uv;
};
std::optional<PolygonTriangle> polygon_as_triangle(const PolygonDesc& polygon);

// A conservative axis-aligned box of primitive i as stored (geometry/primitive_bounds.h).
Box primitive_box(const PolygonSoA& store, std::size_t i);

// Its surface at a hit (geometry/surface_mapping.h).
void map_surface(const PolygonSoA& store, const MappingQuery& query, SurfaceMapping& out);

// The polygon in the scene's list of kinds (geometry/kinds.h).
struct PolygonKind {
  static constexpr std::string_view name = "polygon", plural = "polygons";
  static constexpr bool bounded = true;
  using Method = PolygonMethod;
  static constexpr PolygonMethod product_method = PolygonMethod::crossing;
  using Desc = PolygonDesc;
  using Store = PolygonSoA;
  static Store build(const DescRefs<Desc>& descs, BuildReport& report) { return build_polygons(descs, report); }
  // add(point, margin) for points and margins whose boxes hold the described surface.
  template <class Add>
  static void extent(const Desc& d, Add add) {
    for (const Vec3<float>& p : d.vertices) add(p, 0.0);
  }
};

}  // namespace quiver
