// Planar polygons in SoA: per polygon the unit plane normal (nx, ny, nz), the kept
// axes of the dominant projection, the first vertex projected, the 2D bounding
// rectangle, the lane margin's reach and plane slack (geometry/polygon.h) and
// the vertex range; the vertices live in flat columns, projected relative to
// each polygon's first vertex (pu, pv) and in 3D as given (px, py, pz: the
// ray-space test reads them, so two polygons sharing a vertex read the same
// floats). Packets only: broadcast<F>(i) hands every lane the same polygon.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "geometry/build_report.h"
#include "geometry/primitive_desc.h"
#include "geometry/polygon.h"
#include "geometry/soa.h"

namespace quiver {

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

PolygonSoA build_polygons(std::span<const PolygonDesc> polygons, BuildReport& report);

// Ear-clipping triangulation of a simple (possibly concave) polygon, in its
// dominant projection, keeping the vertex winding. Consecutive duplicates are
// removed first; collinear vertices are clipped without a triangle. Empty for
// input build_polygons would drop. A polygon that is not simple still gives
// n - 2 triangles or fewer, but they need not cover it.
std::vector<std::array<Vec3<float>, 3>> triangulate_polygon(const PolygonDesc& polygon);

// The polygon in the scene's list of kinds (geometry/kinds.h).
struct PolygonKind {
  static constexpr std::string_view name = "polygon", plural = "polygons";
  static constexpr bool bounded = true;
  using Method = PolygonMethod;
  static constexpr PolygonMethod product_method = PolygonMethod::crossing;
  using Desc = PolygonDesc;
  using Store = PolygonSoA;
  static Store build(std::span<const Desc> descs, BuildReport& report) { return build_polygons(descs, report); }
};

}  // namespace quiver
