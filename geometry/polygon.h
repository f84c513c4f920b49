// Ray / planar polygon (n >= 3 vertices, convex or concave), after Haines,
// "Point in Polygon Strategies" (Graphics Gems IV, 1994) and Glassner, An
// Introduction to Ray Tracing, ch. 2:
//   1. plane hit: n.P + d = 0 with unit n, t = -(d + n.o) / (n.dir);
//   2. project the hit point onto the polygon's dominant plane (drop the axis
//      k of n's largest |component|, chosen at build time): coordinates
//      (P[(k+1)%3], P[(k+2)%3]) relative to the first vertex;
//   3. reject points outside the polygon's closed 2D bounding rectangle;
//   4. crossing (even-odd, Jordan curve) test: a +u ray from the point toggles
//      "inside" at every edge it crosses. Half-open rule: an edge (a, b)
//      counts iff (a.v > v) != (b.v > v), so a vertex on the scan line is
//      counted once or not at all, consistently. The crossing lies on the +u
//      side iff sign((v - a.v)(b.u - a.u) - (u - a.u)(b.v - a.v)) matches the
//      edge's upward direction (Haines's multiply form: no division), the
//      product difference from difference_of_products. A point exactly on an
//      edge is inside or outside depending on that edge's direction.
// All lanes share the polygon, so the edge loop is the same for every lane;
// an edge no lane straddles is skipped (it could toggle no lane), except in
// bands, whose few edges are all computed (that branch mispredicted there,
// bench/README.md).
// Edge bands (polygons of many vertices, see PolygonSoA): the v range is cut
// into bands, each listing the edges whose v range meets it; a lane reads
// only its own band's edges. band_of is non-decreasing in v, so every edge
// that straddles a lane's v is in the lane's band: the toggles, and so the
// bits, are those of the full loop. A band's span (BandSpan) decides most
// lanes without edges: left or right of all its edges' u ranges is outside,
// within its widest gap between them of odd parity inside, each bound kept
// kBandSpanMargin of the rectangle's width away from every edge, beyond any
// rounding that could flip a crossing's sign there: the full loop's bits.
// t-range: hit iff tmin < t < tmax. A ray parallel to the plane (n.dir == 0)
// misses, even in the plane; its division is fed 1 (no NaN, no division by 0).
// Masks: only active lanes can hit.
// Output: ng = the unit plane normal (Newell's method; counter-clockwise
// vertex order seen from where ng points); u, v = the hit point's projected
// 2D coordinates relative to the first vertex, (P - V0)[(k+1)%3] and
// (P - V0)[(k+2)%3] (not normalised; for k = 2 they are x and y).
#pragma once

#include <cstddef>
#include <cstdint>

#include "geometry/hit.h"
#include "geometry/plane.h"
#include "simd/ray.h"

namespace quiver {

// Per band: u < edges_lo or u > edges_hi: outside (left or right of every
// edge the band lists); inside_lo < u < inside_hi: inside (an empty range
// when no gap qualifies). Relative coordinates, as the vertices.
struct BandSpan {
  float edges_lo, inside_lo, inside_hi, edges_hi;
};

inline namespace QUIVER_UNIT_NAMESPACE {

// A span bound's distance from the band's edge u ranges, relative to the
// polygon's rectangle width: the crossing test's sign is exact beyond 2^-22
// of it (a difference of products of differences within the rectangle).
inline constexpr float kBandSpanMargin = 0x1p-18f;

template <class F>
struct PolygonLanes {
  Vec3<F> normal;          // unit length
  F d;                     // n.P + d = 0 on the plane
  int axis_u, axis_v;      // the kept axes, (k+1)%3 and (k+2)%3
  F origin_u, origin_v;    // the first vertex, projected
  F umin, umax, vmin, vmax;  // bounding rectangle, relative to the first vertex
  const float* pu;         // vertex_count projected vertices relative to the first
  const float* pv;
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

// Lanes of `straddles` whose +u ray from (u, v) crosses edge a -> b: the
// crossing lies on the +u side iff the point is left of a -> b when b is
// above, right of it when b is below.
template <class F>
inline Mask<F> crossings(const F& u, const F& v, float au, float av, float bu, float bv, const Mask<F>& straddles,
                         const Mask<F>& b_above) {
  // > 0 iff the point is left of a->b.
  const F side = difference_of_products(v - F(av), F(bu - au), u - F(au), F(bv - av));
  return and_not(straddles, masks_differ(side > F(0.f), b_above));
}

// The even-odd parity of the lanes in `lanes` over the edges of one band.
template <class F>
inline Mask<F> band_parity(const PolygonLanes<F>& poly, int band, const F& u, const F& v, const Mask<F>& lanes) {
  const int n = poly.vertex_count;
  Mask<F> inside(false);
  for (std::size_t e = poly.band_first[band]; e < poly.band_first[band + 1]; ++e) {
    const int k = static_cast<int>(poly.band_edges[e]);
    const int j = k == 0 ? n - 1 : k - 1;
    const Mask<F> b_above = F(poly.pv[k]) > v;
    const Mask<F> straddles = masks_differ(F(poly.pv[j]) > v, b_above) && lanes;
    const Mask<F> crossed = crossings(u, v, poly.pu[j], poly.pv[j], poly.pu[k], poly.pv[k], straddles, b_above);
    inside = masks_differ(inside, crossed);
  }
  return inside;
}

// Parity over bands. Each candidate lane's band span decides it or leaves
// it open; the open lanes are grouped by band, each group over its band's
// edges. A group's lanes are found at once: those whose band position x
// lies in [band, band + 1) (the last band: x >= band).
template <class F>
inline Mask<F> banded_parity(const PolygonLanes<F>& poly, const F& u, const F& v, const Mask<F>& candidate) {
  const F x = band_position(v, poly.band_vmin, poly.band_scale);
  alignas(64) float x_lane[kMaxLanes], u_lane[kMaxLanes];
  store_lanes(x, x_lane);
  store_lanes(u, u_lane);
  // Each candidate lane's band, up front: off the group loop's dependency
  // chain (band_of on each group's first lane inside it measured slower).
  int lane_band[kMaxLanes];
  unsigned inside_by_span = 0, open = 0;
  for (unsigned b = lane_bits(candidate); b != 0; b &= b - 1) {
    const int lane = __builtin_ctz(b);
    const int band = band_at(x_lane[lane], poly.band_count);
    lane_band[lane] = band;
    const BandSpan& span = poly.band_spans[band];
    const float lane_u = u_lane[lane];
    const bool inside = lane_u > span.inside_lo && lane_u < span.inside_hi;
    const bool among_edges = lane_u >= span.edges_lo && lane_u <= span.edges_hi;
    inside_by_span |= static_cast<unsigned>(inside) << lane;
    open |= static_cast<unsigned>(among_edges && !inside) << lane;
  }
  Mask<F> inside = mask_from_bits<F>(inside_by_span);
  if (open == 0) return inside;
  const Mask<F> open_lanes = mask_from_bits<F>(open);
  const int last = poly.band_count - 1;
  for (unsigned pending = open; pending != 0;) {
    const int first = __builtin_ctz(pending);
    const int band = lane_band[first];
    const Mask<F> in_band = band < last ? x >= F(static_cast<float>(band)) && x < F(static_cast<float>(band + 1))
                                        : x >= F(static_cast<float>(last));
    const Mask<F> group = in_band && open_lanes;
    pending &= ~(lane_bits(group) | (1u << first));  // the first lane is in its group; cleared in any case
    inside = inside || band_parity(poly, band, u, v, group);
  }
  return inside;
}

}  // namespace polygon_detail

struct PolygonCrossing : RayAsIs {
  template <class F>
  static Mask<F> intersect(const Ray<F>& ray, const PolygonLanes<F>& poly, const F& tmax,
                           const Mask<F>& active, Candidate<F>& out) {
    Mask<F> crosses;
    out.t = plane_crossing(ray, poly.normal, poly.d, crosses);
    out.ng = poly.normal;
    // Projected hit point relative to the first vertex: (o - V0) + t dir.
    const F u = fma(out.t, ray.direction[poly.axis_u], ray.origin[poly.axis_u] - poly.origin_u);
    const F v = fma(out.t, ray.direction[poly.axis_v], ray.origin[poly.axis_v] - poly.origin_v);
    out.u = u;
    out.v = v;
    const Mask<F> in_range = active && crosses && out.t > ray.tmin && out.t < tmax;
    // Bounding rectangle.
    const Mask<F> candidate = in_range && u >= poly.umin && u <= poly.umax && v >= poly.vmin && v <= poly.vmax;
    if (none(candidate)) return candidate;
    if (poly.band_count > 0) return candidate && polygon_detail::banded_parity(poly, u, v, candidate);
    // Crossing test over edges (a, b) = (vertex j, vertex i), j = i - 1 cyclic.
    const int n = poly.vertex_count;
    Mask<F> inside(false);
    float au = poly.pu[n - 1], av = poly.pv[n - 1];
    Mask<F> a_above = F(av) > v;
    for (int i = 0; i < n; ++i) {
      const float bu = poly.pu[i], bv = poly.pv[i];
      const Mask<F> b_above = F(bv) > v;
      const Mask<F> straddles = masks_differ(a_above, b_above);
      if (any(straddles)) {
        inside = masks_differ(inside, polygon_detail::crossings(u, v, au, av, bu, bv, straddles, b_above));
      }
      au = bu;
      av = bv;
      a_above = b_above;
    }
    return candidate && inside;
  }
};

}  // namespace QUIVER_UNIT_NAMESPACE

}  // namespace quiver
