#include "geometry/kinds/polygon.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "geometry/primitive_bounds.h"

namespace quiver {

namespace {

using Vec3d = Vec3<double>;

Vec3d to_double(const Vec3<float>& v) { return {v.x, v.y, v.z}; }

bool same(const Vec3<float>& a, const Vec3<float>& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

enum class Verdict { ok, non_finite, degenerate };

// A polygon that passed every check: its vertices without consecutive
// duplicates, the unit Newell normal and the dominant (dropped) axis.
struct CleanPolygon {
  std::vector<Vec3<float>> vertices;
  Vec3d normal;
  Vec3d centroid;  // of the vertices
  int dropped_axis = 2;
};

// Removes consecutive duplicates, cyclically (the last may equal the first).
std::vector<Vec3<float>> without_consecutive_duplicates(const std::vector<Vec3<float>>& in) {
  std::vector<Vec3<float>> out;
  out.reserve(in.size());
  for (const Vec3<float>& v : in) {
    if (out.empty() || !same(out.back(), v)) out.push_back(v);
  }
  while (out.size() > 1 && same(out.back(), out.front())) out.pop_back();
  return out;
}

Verdict clean(const PolygonDesc& desc, CleanPolygon& result) {
  if (desc.vertices.size() > kMaxPolygonVertices) return Verdict::degenerate;
  for (const Vec3<float>& v : desc.vertices) {
    if (!all_finite(v)) return Verdict::non_finite;
  }
  result.vertices = without_consecutive_duplicates(desc.vertices);
  const std::vector<Vec3<float>>& vs = result.vertices;
  const std::size_t n = vs.size();
  if (n < 3) return Verdict::degenerate;

  const Vec3d normal = newell_normal(vs);
  const Vec3d base = to_double(vs[0]);
  Vec3d lo = base, hi = base, centroid{0, 0, 0};
  for (const Vec3<float>& v : vs) {
    const Vec3d a = to_double(v);
    lo = {std::min(lo.x, a.x), std::min(lo.y, a.y), std::min(lo.z, a.z)};
    hi = {std::max(hi.x, a.x), std::max(hi.y, a.y), std::max(hi.z, a.z)};
    centroid = {centroid.x + (a.x - base.x), centroid.y + (a.y - base.y), centroid.z + (a.z - base.z)};
  }
  const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  const double twice_area = std::sqrt(dot(normal, normal));
  if (!(twice_area > kPolygonMinAreaRatio * extent * extent) || !std::isfinite(twice_area)) {
    return Verdict::degenerate;
  }
  result.normal = {normal.x / twice_area, normal.y / twice_area, normal.z / twice_area};

  // Planarity: every vertex within tolerance * extent of the plane through the centroid.
  centroid = {centroid.x / double(n), centroid.y / double(n), centroid.z / double(n)};
  result.centroid = {base.x + centroid.x, base.y + centroid.y, base.z + centroid.z};
  double farthest = 0;
  for (const Vec3<float>& v : vs) {
    const Vec3d r{double(v.x) - base.x - centroid.x, double(v.y) - base.y - centroid.y,
                  double(v.z) - base.z - centroid.z};
    farthest = std::max(farthest, std::abs(dot(result.normal, r)));
  }
  if (farthest > kPolygonPlanarityTolerance * extent) return Verdict::degenerate;

  // Dominant axis: the largest |normal component| (first of equals).
  const Vec3d m{std::abs(result.normal.x), std::abs(result.normal.y), std::abs(result.normal.z)};
  result.dropped_axis = (m.x >= m.y && m.x >= m.z) ? 0 : (m.y >= m.z ? 1 : 2);
  return Verdict::ok;
}

// Projected vertices that differ from their predecessor (cyclically), as
// many as a polygon without consecutive projected duplicates would keep.
std::size_t distinct_projected(const std::vector<float>& us, const std::vector<float>& vs) {
  const std::size_t n = us.size();
  std::size_t distinct = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t j = k == 0 ? n - 1 : k - 1;
    distinct += us[k] != us[j] || vs[k] != vs[j];
  }
  return distinct;
}

// The span of one band (BandSpan, geometry/polygon.h) from the edges it
// lists, with above(k): band_of(vertex k's v) > band. Between the edges' u
// ranges (sorted by their low ends) lie gaps; the edges right of a gap form
// paths whose end vertices lie outside the band, so each band lane's
// crossings right of the gap have the parity of the above() changes along
// them: the gap is inside iff that parity is odd. The widest such gap
// narrowed by `margin` at each end, the edges' whole u range widened by it.
template <class Above>
BandSpan band_span(const std::vector<float>& us, std::span<const std::uint32_t> edges, const Above& above,
                   double margin) {
  struct Range {
    double lo, hi;
    bool crosses;  // its ends differ in above()
  };
  constexpr float kInf = std::numeric_limits<float>::infinity();
  if (edges.empty()) return {kInf, 0.f, 0.f, -kInf};  // no crossings: outside
  const std::size_t n = us.size();
  std::vector<Range> ranges;
  for (std::uint32_t k : edges) {
    const std::size_t j = k == 0 ? n - 1 : k - 1;
    ranges.push_back({std::min(us[j], us[k]), std::max(us[j], us[k]), above(j) != above(k)});
  }
  std::sort(ranges.begin(), ranges.end(), [](const Range& a, const Range& b) { return a.lo < b.lo; });
  // right_parity[i]: the crossings' parity of ranges i.. (those right of a gap before range i).
  std::vector<bool> right_parity(ranges.size() + 1, false);
  for (std::size_t i = ranges.size(); i-- > 0;) right_parity[i] = right_parity[i + 1] != ranges[i].crosses;
  double reach = ranges.front().hi, widest = 0.0, gap_lo = 0.0, gap_hi = 0.0;
  for (std::size_t i = 1; i < ranges.size(); ++i) {
    if (ranges[i].lo > reach && right_parity[i] && ranges[i].lo - reach > widest) {
      widest = ranges[i].lo - reach;
      gap_lo = reach;
      gap_hi = ranges[i].lo;
    }
    reach = std::max(reach, ranges[i].hi);
  }
  BandSpan span{float(ranges.front().lo - margin), 0.f, 0.f, float(reach + margin)};
  if (gap_hi - gap_lo > 2.0 * margin) {
    span.inside_lo = float(gap_lo + margin);
    span.inside_hi = float(gap_hi - margin);
  }
  return span;
}

// Appends the next polygon's edge bands (or none) for its projected
// vertices (us, vs), whose rectangle is [umin, umax] x [vmin, vmax].
void add_edge_bands(PolygonSoA& soa, const std::vector<float>& us, const std::vector<float>& vs, float umin,
                    float umax, float vmin, float vmax) {
  const std::size_t n = vs.size();
  soa.band_start.push_back(soa.band_first.size());
  int count = n >= kMinBandedVertices ? static_cast<int>(std::min(kMaxEdgeBands, n / kEdgesPerBand)) : 0;
  for (; count >= 2; count /= 2) {
    const float scale = static_cast<float>(count / (static_cast<double>(vmax) - static_cast<double>(vmin)));
    if (!(std::isfinite(scale) && scale > 0.f)) break;
    // Band range of edge k (vertex k - 1 to k), and how many edges each band lists.
    const auto bands_of_edge = [&](std::size_t k) {
      const float a = vs[k == 0 ? n - 1 : k - 1], b = vs[k];
      return std::pair{polygon_detail::band_of(std::min(a, b), vmin, scale, count),
                       polygon_detail::band_of(std::max(a, b), vmin, scale, count)};
    };
    std::vector<std::size_t> offset(static_cast<std::size_t>(count) + 1, 0);
    for (std::size_t k = 0; k < n; ++k) {
      const auto [first, last] = bands_of_edge(k);
      for (int band = first; band <= last; ++band) ++offset[static_cast<std::size_t>(band) + 1];
    }
    for (int band = 0; band < count; ++band) offset[band + 1] += offset[band];
    if (offset.back() > kMaxBandRefsPerEdge * n) continue;  // too many long edges for this many bands
    const std::size_t base = soa.band_edges.size();
    soa.band_edges.resize(base + offset.back());
    std::vector<std::size_t> cursor(offset.begin(), offset.end() - 1);
    for (std::size_t k = 0; k < n; ++k) {
      const auto [first, last] = bands_of_edge(k);
      for (int band = first; band <= last; ++band) {
        soa.band_edges[base + cursor[static_cast<std::size_t>(band)]++] = static_cast<std::uint32_t>(k);
      }
    }
    for (std::size_t o : offset) soa.band_first.push_back(base + o);
    // Rounding each bound to float moves it by at most 2^-24 of the width, well within the margin.
    const double margin = kBandSpanMargin * (static_cast<double>(umax) - static_cast<double>(umin));
    for (int band = 0; band < count; ++band) {
      const std::span<const std::uint32_t> edges(soa.band_edges.data() + base + offset[band],
                                                 offset[band + 1] - offset[band]);
      const auto above = [&](std::size_t k) { return polygon_detail::band_of(vs[k], vmin, scale, count) > band; };
      soa.band_spans.push_back(band_span(us, edges, above, margin));
    }
    soa.band_spans.push_back({});  // beside the last offset, which starts no band
    soa.band_count.push_back(count);
    soa.band_scale.push_back(scale);
    return;
  }
  soa.band_count.push_back(0);
  soa.band_scale.push_back(0.f);
}

}  // namespace

Vec3<double> newell_normal(std::span<const Vec3<float>> vertices) {
  const std::size_t n = vertices.size();
  Vec3d normal{0, 0, 0};
  if (n == 0) return normal;
  const Vec3d base = to_double(vertices[0]);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3d a = to_double(vertices[i]), b = to_double(vertices[(i + 1) % n]);
    const Vec3d ra{a.x - base.x, a.y - base.y, a.z - base.z}, rb{b.x - base.x, b.y - base.y, b.z - base.z};
    normal.x += (ra.y - rb.y) * (ra.z + rb.z);
    normal.y += (ra.z - rb.z) * (ra.x + rb.x);
    normal.z += (ra.x - rb.x) * (ra.y + rb.y);
  }
  return normal;
}

PolygonSoA build_polygons(const DescRefs<PolygonDesc>& polygons, BuildReport& report) {
  PolygonSoA soa;
  for (std::size_t i = 0; i < polygons.size(); ++i) {
    const PolygonDesc& desc = polygons[i];
    CleanPolygon poly;
    const Verdict verdict = clean(desc, poly);
    if (verdict == Verdict::non_finite) {
      ++report.dropped_non_finite;
      continue;
    }
    if (verdict == Verdict::degenerate) {
      ++report.dropped_degenerate;
      continue;
    }
    const Vec3<float> n{float(poly.normal.x), float(poly.normal.y), float(poly.normal.z)};
    // d for the rounded normal through the centroid: n.C + d = 0 (the lane
    // margin's reach; the kernel's t is anchored at the first vertex).
    const Vec3d& c = poly.centroid;
    const float d = float(-(double(n.x) * c.x + double(n.y) * c.y + double(n.z) * c.z));
    const Vec3<float>& v0 = poly.vertices[0];
    const int au = (poly.dropped_axis + 1) % 3, av = (poly.dropped_axis + 2) % 3;

    // Projected vertices relative to the first, all kept; the lane margin's
    // reach (largest |V|_1 + |d|) and plane slack (largest |n.(V - V0)|: the
    // vertices' distance from t's plane, the one through the first vertex).
    std::vector<float> us, vs;
    bool all_finite = std::isfinite(d);
    double reach = 0.0, slack = 0.0;
    for (const Vec3<float>& p : poly.vertices) {
      const float u = p[au] - v0[au], v = p[av] - v0[av];
      all_finite = all_finite && std::isfinite(u) && std::isfinite(v);
      us.push_back(u);
      vs.push_back(v);
      reach = std::max(reach, std::abs(double(p.x)) + std::abs(double(p.y)) + std::abs(double(p.z)));
      slack = std::max(slack, std::abs(double(n.x) * (double(p.x) - v0.x) + double(n.y) * (double(p.y) - v0.y) +
                                       double(n.z) * (double(p.z) - v0.z)));
    }
    if (!all_finite) {
      ++report.dropped_non_finite;
      continue;
    }
    if (distinct_projected(us, vs) < 3) {
      ++report.dropped_degenerate;
      continue;
    }
    soa.source.push_back(static_cast<std::uint32_t>(i));
    soa.nx.push_back(n.x);
    soa.ny.push_back(n.y);
    soa.nz.push_back(n.z);
    soa.origin_u.push_back(v0[au]);
    soa.origin_v.push_back(v0[av]);
    soa.umin.push_back(*std::min_element(us.begin(), us.end()));
    soa.umax.push_back(*std::max_element(us.begin(), us.end()));
    soa.vmin.push_back(*std::min_element(vs.begin(), vs.end()));
    soa.vmax.push_back(*std::max_element(vs.begin(), vs.end()));
    // Rounded up: float() may round down by 2^-24.
    constexpr double kUp = 1.0 + 0x1p-20;
    soa.reach.push_back(float((reach + std::abs(double(d))) * kUp));
    soa.plane_slack.push_back(float(slack * kUp));
    soa.axis_u.push_back(au);
    soa.axis_v.push_back(av);
    soa.vertex_count.push_back(static_cast<std::int32_t>(us.size()));
    soa.first_vertex.push_back(soa.pu.size());
    soa.pu.insert(soa.pu.end(), us.begin(), us.end());
    soa.pv.insert(soa.pv.end(), vs.begin(), vs.end());
    for (const Vec3<float>& p : poly.vertices) {
      soa.px.push_back(p.x);
      soa.py.push_back(p.y);
      soa.pz.push_back(p.z);
    }
    add_edge_bands(soa, us, vs, soa.umin.back(), soa.umax.back(), soa.vmin.back(), soa.vmax.back());
  }
  soa.count = soa.nx.size();
  report.kept += soa.count;
  for (AlignedFloats* c : soa.polygon_columns()) pad_column(*c, soa.count);
  for (AlignedInts* c : soa.polygon_int_columns()) pad_column(*c, soa.count);
  soa.first_vertex.resize(padded_size(soa.count), soa.first_vertex.empty() ? 0 : soa.first_vertex.back());
  soa.band_start.resize(padded_size(soa.count), soa.band_first.size());
  return soa;
}

std::size_t PolygonSoA::memory_bytes() const {
  std::size_t bytes = 0;
  for (const AlignedFloats* c : polygon_columns()) bytes += bytes_of(*c);
  for (const AlignedFloats* c : vertex_columns()) bytes += bytes_of(*c);
  for (const AlignedInts* c : polygon_int_columns()) bytes += bytes_of(*c);
  for (const std::vector<std::size_t>* c : {&first_vertex, &band_start, &band_first}) {
    bytes += c->capacity() * sizeof(std::size_t);
  }
  return bytes + band_edges.capacity() * sizeof(std::uint32_t) + band_spans.capacity() * sizeof(BandSpan) +
         source.capacity() * sizeof(std::uint32_t);
}

namespace {

struct Point2d {
  double x, y;
};

// Twice the signed area of (a, b, c): > 0 when counter-clockwise.
double orient(const Point2d& a, const Point2d& b, const Point2d& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

}  // namespace

std::optional<PolygonTriangle> polygon_as_triangle(const PolygonDesc& polygon) {
  // Vertices that differ from their predecessor (cyclically): what cleaning
  // keeps, counted without building it, so larger polygons skip the checks.
  const std::vector<Vec3<float>>& given = polygon.vertices;
  std::size_t distinct = 0;
  for (std::size_t k = 0; k < given.size(); ++k) distinct += !same(given[k], given[k == 0 ? given.size() - 1 : k - 1]);
  if (distinct != 3) return std::nullopt;
  CleanPolygon poly;
  if (clean(polygon, poly) != Verdict::ok || poly.vertices.size() != 3) return std::nullopt;
  const std::vector<Vec3<float>>& vs = poly.vertices;
  const int au = (poly.dropped_axis + 1) % 3, av = (poly.dropped_axis + 2) % 3;
  // As the kernel's u, v: float differences from the first vertex.
  auto uv = [&](std::size_t k) { return std::array<float, 2>{vs[k][au] - vs[0][au], vs[k][av] - vs[0][av]}; };
  return PolygonTriangle{{vs[0], vs[1], vs[2]}, {uv(0), uv(1), uv(2)}};
}

std::vector<std::array<Vec3<float>, 3>> triangulate_polygon(const PolygonDesc& polygon) {
  std::vector<std::array<Vec3<float>, 3>> triangles;
  CleanPolygon poly;
  if (clean(polygon, poly) != Verdict::ok) return triangles;
  const std::vector<Vec3<float>>& vs = poly.vertices;
  const int au = (poly.dropped_axis + 1) % 3, av = (poly.dropped_axis + 2) % 3;
  std::vector<Point2d> p;
  p.reserve(vs.size());
  for (const Vec3<float>& v : vs) p.push_back({double(v[au]) - vs[0][au], double(v[av]) - vs[0][av]});
  // Winding sign of the projection: ears are convex in this sense.
  double area = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Point2d& a = p[i];
    const Point2d& b = p[(i + 1) % p.size()];
    area += a.x * b.y - a.y * b.x;
  }
  const double sense = area >= 0 ? 1.0 : -1.0;

  std::vector<int> ring(vs.size());
  for (std::size_t i = 0; i < ring.size(); ++i) ring[i] = static_cast<int>(i);
  triangles.reserve(vs.size() - 2);
  auto emit = [&](int a, int b, int c) { triangles.push_back({vs[a], vs[b], vs[c]}); };
  auto coincides = [&](int r, int a) { return p[r].x == p[a].x && p[r].y == p[a].y; };

  std::size_t cursor = 0;
  while (ring.size() > 3) {
    const std::size_t m = ring.size();
    bool clipped = false;
    std::size_t best = m;  // most convex corner, for the no-ear fallback
    double best_turn = 0;
    for (std::size_t step = 0; step < m && !clipped; ++step) {
      const std::size_t k = (cursor + step) % m;
      const int a = ring[(k + m - 1) % m], b = ring[k], c = ring[(k + 1) % m];
      const double turn = sense * orient(p[a], p[b], p[c]);
      if (turn == 0) {  // collinear corner: no area to cover
        ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(k));
        cursor = k;
        clipped = true;
        break;
      }
      if (turn < 0) continue;  // reflex corner
      if (turn > best_turn) {
        best_turn = turn;
        best = k;
      }
      // An ear holds no other ring vertex in its closed triangle.
      bool empty = true;
      for (const int r : ring) {
        if (r == a || r == b || r == c || coincides(r, a) || coincides(r, b) || coincides(r, c)) continue;
        if (sense * orient(p[a], p[b], p[r]) >= 0 && sense * orient(p[b], p[c], p[r]) >= 0 &&
            sense * orient(p[c], p[a], p[r]) >= 0) {
          empty = false;
          break;
        }
      }
      if (!empty) continue;
      emit(a, b, c);
      ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(k));
      cursor = k;
      clipped = true;
    }
    if (clipped) continue;
    // No ear (not simple, or rounding): clip the most convex corner, or drop one.
    const std::size_t k = best < m ? best : 0;
    if (best < m) emit(ring[(k + m - 1) % m], ring[k], ring[(k + 1) % m]);
    ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(k));
    cursor = k;
  }
  if (sense * orient(p[ring[0]], p[ring[1]], p[ring[2]]) > 0) emit(ring[0], ring[1], ring[2]);
  return triangles;
}

Box primitive_box(const PolygonSoA& g, std::size_t i) {
  // The vertices as stored (the ray-space test's) and lifted from their
  // projections onto the plane through the first one, in double (the plane
  // hit's).
  const int au = g.axis_u[i], av = g.axis_v[i], ak = 3 - au - av;
  const double n[3] = {g.nx[i], g.ny[i], g.nz[i]};
  const std::size_t first = g.first_vertex[i];
  const double v0k = ak == 0 ? g.px[first] : (ak == 1 ? g.py[first] : g.pz[first]);
  Box b = empty_box();
  for (std::int32_t k = 0; k < g.vertex_count[i]; ++k) {
    const std::size_t at = g.first_vertex[i] + static_cast<std::size_t>(k);
    grow(b, Vec3<float>{g.px[at], g.py[at], g.pz[at]});
    double p[3];
    p[au] = static_cast<double>(g.origin_u[i]) + g.pu[at];
    p[av] = static_cast<double>(g.origin_v[i]) + g.pv[at];
    p[ak] = v0k - (n[au] * g.pu[at] + n[av] * g.pv[at]) / n[ak];
    grow_ball(b, p, 0.0);
  }
  return b;
}

namespace {

double cross2(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

// (s, t) with p = a + s e + t f + s t g for a quad a, b, c, d in 2D
// (e = b - a, f = d - a, g = a - b + c - d): t from the quadratic
// cross(h - t f, e + t g) = 0, s from the better-conditioned axis.
void inverse_bilinear(const double q[4][2], double px, double py, float& s_out, float& t_out) {
  const double ex = q[1][0] - q[0][0], ey = q[1][1] - q[0][1];
  const double fx = q[3][0] - q[0][0], fy = q[3][1] - q[0][1];
  const double gx = q[0][0] - q[1][0] + q[2][0] - q[3][0], gy = q[0][1] - q[1][1] + q[2][1] - q[3][1];
  const double hx = px - q[0][0], hy = py - q[0][1];
  const double k2 = cross2(gx, gy, fx, fy);
  const double k1 = cross2(ex, ey, fx, fy) + cross2(hx, hy, gx, gy);
  const double k0 = cross2(hx, hy, ex, ey);
  double t;
  if (std::fabs(k2) <= 1e-12 * std::fabs(k1)) {
    t = k1 != 0.0 ? -k0 / k1 : 0.0;  // a parallelogram: linear
  } else {
    const double w = std::sqrt(std::max(k1 * k1 - 4.0 * k0 * k2, 0.0));
    const double t1 = (-k1 - w) / (2.0 * k2), t2 = (-k1 + w) / (2.0 * k2);
    t = (t1 >= -1e-6 && t1 <= 1.0 + 1e-6) ? t1 : t2;
  }
  const double dx = ex + gx * t, dy = ey + gy * t;
  const double s = std::fabs(dx) >= std::fabs(dy) ? (dx != 0.0 ? (hx - fx * t) / dx : 0.0)
                                                  : (hy - fy * t) / dy;
  s_out = float(s);
  t_out = float(t);
}

}  // namespace

// A quad's bilinear (u, v) (inverse bilinear mapping in the polygon's 2D
// projection); other polygons keep the kernel's (u, v), the point in the
// projection's two axes, like a plane's.
void map_surface(const PolygonSoA& p, const MappingQuery& q, SurfaceMapping& out) {
  const Hit<float>& hit = q.hit;
  const std::uint32_t i = q.index;
  const int axis_u = p.axis_u[i], axis_v = p.axis_v[i];
  for (int a = 0; a < 2; ++a) {
    out.du[a] = q.dp[a][axis_u];
    out.dv[a] = q.dp[a][axis_v];
  }
  if (!q.textured || p.vertex_count[i] != 4) return;
  double quad[4][2];
  for (int k = 0; k < 4; ++k) {
    quad[k][0] = p.pu[p.first_vertex[i] + k];
    quad[k][1] = p.pv[p.first_vertex[i] + k];
  }
  inverse_bilinear(quad, hit.u, hit.v, out.u, out.v);
  // The bilinear map's change by a finite difference over the footprint.
  for (int a = 0; a < 2 && q.footprint; ++a) {
    float u_moved, v_moved;
    inverse_bilinear(quad, double(hit.u) + out.du[a], double(hit.v) + out.dv[a], u_moved, v_moved);
    out.du[a] = u_moved - out.u;
    out.dv[a] = v_moved - out.v;
  }
}

}  // namespace quiver
