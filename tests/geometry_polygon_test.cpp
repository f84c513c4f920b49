#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "geometry/kind_streams.h"
#include "tests/support/kernel_checks.h"
#include "tests/support/ray_sampling.h"
#include "tests/support/study_streams.h"

namespace quiver {
namespace {

using testing::RaySampler;

constexpr float kInf = std::numeric_limits<float>::infinity();

struct Point2 {
  double x, y;
};

PolygonSoA polygons_of(const std::vector<PolygonDesc>& descs, BuildReport* out = nullptr) {
  BuildReport report;
  PolygonSoA soa = build_polygons(descs, report);
  if (out) *out = report;
  return soa;
}

Hit<float> closest(const Ray<float>& ray, const PolygonSoA& polygons) {
  return testing::closest_hit(study_polygon_streams<KernelUnit::scalar>(PolygonMethod::crossing), ray, polygons);
}

// 2D outline (x, y) placed in the plane z = z0 + sx x + sy y.
PolygonDesc in_plane(const std::vector<Point2>& outline, float z0 = 0.f, float sx = 0.f, float sy = 0.f) {
  PolygonDesc d;
  for (const Point2& p : outline) {
    const float x = float(p.x), y = float(p.y);
    d.vertices.push_back({x, y, z0 + sx * x + sy * y});
  }
  return d;
}

// The crossing rule in the polygon's own projection, in double (the band
// spans' parity): half-open straddle, crossing on the +x side iff the point
// is left of a->b for an upward edge (right of it downward).
bool crossing_reference(const std::vector<Point2>& poly, double x, double y) {
  bool inside = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Point2 a = poly[j], b = poly[i];
    const bool b_above = b.y > y;
    if ((a.y > y) == b_above) continue;
    const double side = (y - a.y) * (b.x - a.x) - (x - a.x) * (b.y - a.y);
    if ((side > 0) == b_above) inside = !inside;
  }
  return inside;
}

// The kernel's ray-space rule (geometry/kinds/polygon.h) in double for a ray along
// -z through (x, y): kz = z, swapped (d.z < 0), so the sheared frame is
// x' = Y - y, y' = X - x; an edge straddles iff its ends differ in y' > 0
// and crosses iff lo.x' hi.y' - lo.y' hi.x' > 0 (lo, hi: its ends below and above).
bool ray_space_reference(const std::vector<Point2>& poly, double x, double y) {
  bool inside = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Point2 a{poly[j].y - y, poly[j].x - x}, b{poly[i].y - y, poly[i].x - x};
    const bool b_above = b.y > 0;
    if ((a.y > 0) == b_above) continue;
    const Point2 lo = b_above ? a : b, hi = b_above ? b : a;
    if (lo.x * hi.y - lo.y * hi.x > 0) inside = !inside;
  }
  return inside;
}

// Sunday's winding number (a different algorithm from the kernel's).
int winding_number(const std::vector<Point2>& poly, double x, double y) {
  int wn = 0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Point2 a = poly[i], b = poly[(i + 1) % poly.size()];
    const double left = (b.x - a.x) * (y - a.y) - (x - a.x) * (b.y - a.y);
    if (a.y <= y) {
      if (b.y > y && left > 0) ++wn;
    } else if (b.y <= y && left < 0) {
      --wn;
    }
  }
  return wn;
}

// Euclidean distance from (x, y) to the polygon's boundary.
double boundary_distance(const std::vector<Point2>& poly, double x, double y) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Point2 a = poly[i], b = poly[(i + 1) % poly.size()];
    const double ex = b.x - a.x, ey = b.y - a.y;
    const double len2 = ex * ex + ey * ey;
    const double s = len2 > 0 ? std::clamp(((x - a.x) * ex + (y - a.y) * ey) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, std::hypot(x - (a.x + s * ex), y - (a.y + s * ey)));
  }
  return best;
}

std::vector<Point2> l_shape() { return {{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 3}, {0, 3}}; }

// 50 teeth of width 1 (x in [2k, 2k+1], y up to 5) on a spine y in [0, 1]: 200 vertices.
std::vector<Point2> comb() {
  constexpr int kTeeth = 50;
  std::vector<Point2> p{{0, 0}, {2 * kTeeth - 1, 0}};
  for (int k = kTeeth - 1; k >= 0; --k) {
    p.push_back({2.0 * k + 1, 5});
    p.push_back({2.0 * k, 5});
    if (k > 0) {
      p.push_back({2.0 * k, 1});
      p.push_back({2.0 * k - 1, 1});
    }
  }
  return p;
}

// Five-pointed star: outer radius 2 (first vertex at the top), inner 0.8.
std::vector<Point2> star() {
  std::vector<Point2> p;
  for (int i = 0; i < 10; ++i) {
    const double angle = std::numbers::pi / 2 + i * std::numbers::pi / 5;
    const double r = i % 2 ? 0.8 : 2.0;
    p.push_back({double(float(r * std::cos(angle))), double(float(r * std::sin(angle)))});
  }
  return p;
}

TEST(PolygonKernel, SquareInPlaneYHandComputed) {
  // Dominant axis y is dropped: u = z - z0, v = x - x0.
  const PolygonSoA sq = polygons_of({{{{0, 1, 0}, {0, 1, 2}, {2, 1, 2}, {2, 1, 0}}}});
  ASSERT_EQ(sq.size(), 1u);
  const Hit<float> h = closest({{0.5f, 5, 1.5f}, {0, -2, 0}, 0.f, kInf}, sq);
  ASSERT_EQ(h.id, 0);
  EXPECT_FLOAT_EQ(h.t, 2.f);
  EXPECT_FLOAT_EQ(h.u, 1.5f);
  EXPECT_FLOAT_EQ(h.v, 0.5f);
  EXPECT_FLOAT_EQ(h.ng.x, 0.f);
  EXPECT_FLOAT_EQ(h.ng.y, 1.f);  // (B - A) x (C - A) points to +y
  EXPECT_FLOAT_EQ(h.ng.z, 0.f);
  EXPECT_EQ(closest({{2.5f, 5, 1}, {0, -1, 0}, 0.f, kInf}, sq).id, kNoHit);      // beside it
  EXPECT_EQ(closest({{0.5f, 5, 1.5f}, {0, -2, 0}, 0.f, 2.f}, sq).id, kNoHit);    // t == tmax
  EXPECT_EQ(closest({{0.5f, 5, 1.5f}, {0, -2, 0}, 2.f, kInf}, sq).id, kNoHit);   // t == tmin
  EXPECT_EQ(closest({{0.5f, 5, 1.5f}, {0, 2, 0}, 0.f, kInf}, sq).id, kNoHit);    // behind
  EXPECT_EQ(closest({{0.5f, -3, 1.5f}, {0, 1, 0}, 0.f, kInf}, sq).id, 0);        // from below: both sides hit
}

TEST(PolygonKernel, TriangleEqualComponentsDropX) {
  const PolygonSoA tri = polygons_of({{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}});
  ASSERT_EQ(tri.size(), 1u);
  EXPECT_EQ(tri.axis_u[0], 1);  // |n| components tie: x dropped, u = y, v = z
  EXPECT_EQ(tri.axis_v[0], 2);
  const Hit<float> h = closest({{0, 0, 0}, {1, 1, 1}, 0.f, kInf}, tri);
  ASSERT_EQ(h.id, 0);
  EXPECT_NEAR(h.t, 1.0 / 3, 1e-7);
  EXPECT_NEAR(h.u, 1.0 / 3, 1e-7);
  EXPECT_NEAR(h.v, 1.0 / 3, 1e-7);
  const float inv_sqrt3 = float(1 / std::sqrt(3.0));
  EXPECT_FLOAT_EQ(h.ng.x, inv_sqrt3);
  EXPECT_FLOAT_EQ(h.ng.y, inv_sqrt3);
  EXPECT_FLOAT_EQ(h.ng.z, inv_sqrt3);
  // (0.6, 0.6, -0.2) is in the plane but outside the triangle.
  EXPECT_EQ(closest(RaySampler(1).toward({0, 0, 0}, {0.6f, 0.6f, -0.2f}), tri).id, kNoHit);
  EXPECT_EQ(closest(RaySampler(1).toward({0, 0, 0}, {0.2f, 0.3f, 0.5f}), tri).id, 0);
}

TEST(PolygonKernel, LShapedConcave) {
  const PolygonSoA l = polygons_of({in_plane(l_shape(), -1.f)});
  ASSERT_EQ(l.size(), 1u);
  auto down = [](float x, float y) { return Ray<float>{{x, y, 2}, {0, 0, -1}, 0.f, kInf}; };
  for (const Point2 p : std::vector<Point2>{{0.5, 2.5}, {2.5, 0.5}, {0.5, 0.5}, {0.9, 2.9}}) {
    const Hit<float> h = closest(down(float(p.x), float(p.y)), l);
    ASSERT_EQ(h.id, 0) << p.x << ", " << p.y;
    EXPECT_FLOAT_EQ(h.t, 3.f);
    EXPECT_FLOAT_EQ(h.u, float(p.x));  // first vertex at the origin: u, v = x, y
    EXPECT_FLOAT_EQ(h.v, float(p.y));
    EXPECT_FLOAT_EQ(h.ng.z, 1.f);
  }
  for (const Point2 p : std::vector<Point2>{{2, 2}, {1.1, 1.1}, {2.9, 2.9}, {-0.1, 0.5}, {0.5, 3.1}}) {
    EXPECT_EQ(closest(down(float(p.x), float(p.y)), l).id, kNoHit) << p.x << ", " << p.y;  // notch, outside
  }
}

TEST(PolygonKernel, StarConcaveInPlaneX) {
  // Outline (y, z) in the plane x = 3; x is dropped: u = y - y0, v = z - z0.
  PolygonDesc d;
  for (const Point2& p : star()) d.vertices.push_back({3.f, float(p.x), float(p.y)});
  const PolygonSoA s = polygons_of({d});
  ASSERT_EQ(s.size(), 1u);
  auto from_plus_x = [](double y, double z) { return Ray<float>{{10, float(y), float(z)}, {-1, 0, 0}, 0.f, kInf}; };
  const Hit<float> center = closest(from_plus_x(0, 0), s);
  ASSERT_EQ(center.id, 0);
  EXPECT_FLOAT_EQ(center.t, 7.f);
  EXPECT_FLOAT_EQ(center.ng.x, 1.f);
  EXPECT_NEAR(center.u, 0.0, 1e-6);
  EXPECT_FLOAT_EQ(center.v, -2.f);
  for (int i = 0; i < 5; ++i) {
    const double tip = std::numbers::pi / 2 + i * 2 * std::numbers::pi / 5;
    const double notch = tip + std::numbers::pi / 5;
    EXPECT_EQ(closest(from_plus_x(1.8 * std::cos(tip), 1.8 * std::sin(tip)), s).id, 0) << i;
    EXPECT_EQ(closest(from_plus_x(1.2 * std::cos(notch), 1.2 * std::sin(notch)), s).id, kNoHit) << i;
  }
}

TEST(PolygonKernel, Comb200VerticesTeethAndGaps) {
  const std::vector<Point2> outline = comb();
  ASSERT_EQ(outline.size(), 200u);
  const PolygonSoA c = polygons_of({in_plane(outline, 1.f, 0.5f, 0.25f)});  // tilted, z dominant
  ASSERT_EQ(c.size(), 1u);
  ASSERT_EQ(c.vertex_count[0], 200);
  int hits = 0;
  for (int i = -2; i < 204; ++i) {
    for (int j = -1; j < 13; ++j) {
      const double x = 0.25 + 0.5 * i, y = 0.5 * j + 0.25;
      const bool expected = x > 0 && x < 99 && y > 0 && (y < 1 || (y < 5 && int(std::floor(x)) % 2 == 0));
      const Hit<float> h = closest({{float(x), float(y), 100}, {0, 0, -1}, 0.f, kInf}, c);
      ASSERT_EQ(h.id == 0, expected) << x << ", " << y;
      hits += h.id == 0;
    }
  }
  EXPECT_GT(hits, 1000);
}

// Hit points exactly on vertices, on edges and on scan lines through
// vertices of concave polygons with horizontal edges, local extrema and a
// saddle, one small and one of 35 vertices (edge bands: lanes decided by a
// band's span or edges, those near an edge in ray space): straight-down rays
// keep the projected point exact, so the kernel must equal the
// double-precision rule on every point and the winding number off the
// boundary (each vertex on the scan line counted once).
TEST(PolygonStability, RaysThroughVerticesAndAlongEdges) {
  const std::vector<Point2> small{{0, 0}, {8, 0}, {8, 4}, {7, 4}, {7, 2}, {6, 2}, {6, 4}, {5, 3},
                                  {4, 4}, {3, 2}, {2, 3}, {1, 2}, {1, 5}, {0, 5}};
  // A comb: square teeth on the right, saw teeth on the left.
  std::vector<Point2> comb{{0, 0}, {10, 0}};
  for (int k = 10; k > 4; --k) {
    comb.insert(comb.end(), {{double(k), 4}, {k - 0.5, 4}, {k - 0.5, 2}, {k - 1.0, 2}});
  }
  for (int k = 4; k > 0; --k) comb.insert(comb.end(), {{double(k), 3}, {k - 0.5, 1.5}});
  comb.push_back({0, 3});
  for (const std::vector<Point2>* outline : {&small, static_cast<const std::vector<Point2>*>(&comb)}) {
    for (const float tilt : {0.f, 0.5f}) {
      const PolygonSoA p = polygons_of({in_plane(*outline, -2.f, tilt, 0.25f * tilt)});
      ASSERT_EQ(p.size(), 1u);
      EXPECT_EQ(p.band_count[0] > 0, outline == &comb) << outline->size() << " vertices";
      int on_vertex = 0, on_edge = 0, on_vertex_scanline = 0, hits = 0, wrong_off_boundary = 0, wrong_on_boundary = 0;
      std::string first_wrong;
      for (int i = -4; i <= 44; ++i) {
        for (int j = -4; j <= 24; ++j) {
          const double x = 0.25 * i, y = 0.25 * j;
          const Hit<float> h = closest({{float(x), float(y), 50}, {0, 0, -1}, 0.f, kInf}, p);
          const bool kernel = h.id == 0;
          hits += kernel;
          const double dist = boundary_distance(*outline, x, y);
          bool vertex_row = false, is_vertex = false;
          for (const Point2& v : *outline) {
            vertex_row = vertex_row || v.y == y;
            is_vertex = is_vertex || (v.x == x && v.y == y);
          }
          on_vertex += is_vertex;
          on_edge += dist == 0 && !is_vertex;
          bool wrong;
          if (dist > 0) {  // off the boundary: the true answer
            wrong = kernel != (winding_number(*outline, x, y) != 0);
            wrong_off_boundary += wrong;
            on_vertex_scanline += vertex_row;
          } else {  // on it: the ray-space half-open rule along +x, evaluated exactly
            wrong = kernel != ray_space_reference(*outline, x, y);
            wrong_on_boundary += wrong;
          }
          if (wrong && first_wrong.empty()) first_wrong = std::to_string(x) + ", " + std::to_string(y);
        }
      }
      ASSERT_EQ(wrong_off_boundary, 0) << "tilt " << tilt << ", first wrong point " << first_wrong;
      ASSERT_EQ(wrong_on_boundary, 0) << "tilt " << tilt << ", first wrong point " << first_wrong;
      EXPECT_EQ(on_vertex, int(outline->size()));
      EXPECT_GT(on_edge, 100);
      EXPECT_GT(on_vertex_scanline, 100);
      EXPECT_GT(hits, 300);
    }
  }
}

TEST(PolygonStability, ParallelRaysMissWithoutNaN) {
  const PolygonSoA l = polygons_of({in_plane(l_shape(), 1.f)});
  EXPECT_EQ(closest({{-1, 0.5f, 1}, {1, 0, 0}, 0.f, kInf}, l).id, kNoHit);   // in the plane, across it
  EXPECT_EQ(closest({{0.5f, 0.5f, 1}, {0, 1, 0}, 0.f, kInf}, l).id, kNoHit);  // in the plane, from inside
  EXPECT_EQ(closest({{0.5f, 0.5f, 2}, {1, 1, 0}, 0.f, kInf}, l).id, kNoHit);  // above it
  Candidate<float> c;
  const Ray<float> in_plane_ray{{0.5f, 0.5f, 1}, {1, 0, 0}, 0.f, kInf};
  EXPECT_FALSE(PolygonCrossing::intersect(PolygonCrossing::prepare(in_plane_ray), l.broadcast<float>(0), kInf, true, c));
  EXPECT_TRUE(std::isfinite(c.t));
  EXPECT_TRUE(std::isfinite(c.u) && std::isfinite(c.v));
}

TEST(PolygonKernel, ClosestOfSeveralAndInactiveLanes) {
  const PolygonSoA ps = polygons_of({in_plane(l_shape(), 0.f), in_plane(l_shape(), 1.f), in_plane(l_shape(), 1.f)});
  const Hit<float> h = closest({{0.5f, 0.5f, 5}, {0, 0, -1}, 0.f, kInf}, ps);
  EXPECT_EQ(h.id, 1);  // first of the two equal hits
  EXPECT_FLOAT_EQ(h.t, 4.f);
  Candidate<float> c;
  EXPECT_FALSE(PolygonCrossing::intersect(PolygonCrossing::prepare(Ray<float>{{0.5f, 0.5f, 5}, {0, 0, -1}, 0.f, kInf}),
                                          ps.broadcast<float>(0), kInf, false, c));
}

TEST(PolygonBuild, DropsDegenerateNonPlanarAndNonFinite) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const PolygonDesc square{{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}};
  std::vector<PolygonDesc> descs{
      {{{0, 0, 0}, {1, 0, 0}, {nan, 1, 0}}},                            // NaN
      {{{0, 0, 0}, {kInf, 0, 0}, {1, 1, 0}}},                           // Inf
      {{{0, 0, 0}, {1, 0, 0}}},                                         // two vertices
      {{{0, 0, 0}, {0, 0, 0}, {1, 0, 0}, {1, 0, 0}}},                   // two after de-duplication
      {{{0, 0, 0}, {1, 0, 0}, {0, 0, 0}}},                              // A B A: two, cyclically
      {{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}},                              // collinear: zero area
      {{{0, 0, 0}, {1, 0, 0}, {1, 1, 1e-3f}, {0, 1, 0}}},               // 1e-3 of extent off the plane
      {{{-3e38f, -3e38f, 0}, {3e38f, -3e38f, 0}, {3e38f, 3e38f, 0}}},   // projection overflows
      {{{0, 0, 0}, {1, 0, 0}, {1, 1, 2e-5f}, {0, 1, 0}}},               // 2e-5 of extent: planar enough
      {{{0, 0, 0}, {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 0}}},  // duplicates, closing copy
      square,
  };
  PolygonDesc huge;
  huge.vertices.resize(kMaxPolygonVertices + 1, {0, 0, 0});
  descs.push_back(huge);
  BuildReport report;
  const PolygonSoA soa = polygons_of(descs, &report);
  ASSERT_EQ(soa.size(), 3u);
  EXPECT_EQ(report.kept, 3u);
  EXPECT_EQ(report.dropped_non_finite, 3u);
  EXPECT_EQ(report.dropped_degenerate, 6u);
  EXPECT_EQ(soa.vertex_count[1], 4);  // duplicates removed
  EXPECT_EQ(soa.vertex_count[2], 4);
  EXPECT_EQ(soa.first_vertex[2], 8u);
  EXPECT_EQ(soa.nx.size() % kMaxLanes, 0u);
  for (const AlignedFloats* column : {&soa.nx, &soa.ny, &soa.nz, &soa.umin, &soa.umax, &soa.pu, &soa.pv}) {
    for (float v : *column) EXPECT_TRUE(std::isfinite(v));
  }
  EXPECT_EQ(soa.vertex_count[7], 4);  // padding copies the last polygon
}

// Every triangle has area, whatever the outline: collinear corners are
// dropped, not emitted, down to the last three (lattice outlines, many of
// them folding back along an edge, as (2,2) (0,1) (0,2) (0,0) does).
TEST(PolygonTriangulate, NeverEmitsATriangleWithoutArea) {
  RaySampler s(41);
  std::vector<PolygonDesc> outlines{{{{2, 2, 0}, {0, 1, 0}, {0, 2, 0}, {0, 0, 0}}}};
  for (int k = 0; k < 20000; ++k) {
    PolygonDesc d;
    const int n = s.uniform_int(4, 8);
    for (int i = 0; i < n; ++i) d.vertices.push_back({float(s.uniform_int(0, 2)), float(s.uniform_int(0, 2)), 0.f});
    outlines.push_back(d);
  }
  std::size_t triangles = 0;
  for (const PolygonDesc& d : outlines) {
    for (const auto& t : triangulate_polygon(d)) {
      const double twice_area = (double(t[1].x) - t[0].x) * (double(t[2].y) - t[0].y) -
                                (double(t[1].y) - t[0].y) * (double(t[2].x) - t[0].x);
      ASSERT_NE(twice_area, 0.0) << t[0].x << "," << t[0].y << " " << t[1].x << "," << t[1].y << " " << t[2].x << ","
                                 << t[2].y;
      ++triangles;
    }
  }
  EXPECT_GT(triangles, 10000u);
}

TEST(PolygonTriangulate, CoversConcavePolygonsExactlyOnce) {
  RaySampler s(3);
  std::vector<std::vector<Point2>> outlines{l_shape(), comb(), star()};
  for (int k = 0; k < 20; ++k) {  // random star-shaped, mostly concave
    std::vector<Point2> p;
    const int n = s.uniform_int(5, 40);
    for (int i = 0; i < n; ++i) {
      const double a = 2 * std::numbers::pi * i / n, r = s.uniform(0.2f, 1.f);
      p.push_back({double(float(r * std::cos(a))), double(float(r * std::sin(a)))});
    }
    outlines.push_back(p);
  }
  for (std::size_t k = 0; k < outlines.size(); ++k) {
    std::vector<Point2> outline = outlines[k];
    if (k % 2) std::reverse(outline.begin(), outline.end());  // both windings
    const auto tris = triangulate_polygon(in_plane(outline));
    // n - 2 triangles, fewer where clipping leaves collinear corners (the comb's spine).
    ASSERT_LE(tris.size(), outline.size() - 2) << k;
    if (k != 1) {
      ASSERT_EQ(tris.size(), outline.size() - 2) << k;
    }
    double poly_area = 0;
    for (std::size_t i = 0; i < outline.size(); ++i) {
      const Point2 a = outline[i], b = outline[(i + 1) % outline.size()];
      poly_area += 0.5 * (a.x * b.y - a.y * b.x);
    }
    double tri_area = 0;
    for (const auto& t : tris) {
      const double signed_area =
          0.5 * ((double(t[1].x) - t[0].x) * (double(t[2].y) - t[0].y) - (double(t[1].y) - t[0].y) * (double(t[2].x) - t[0].x));
      EXPECT_GT(signed_area * poly_area, 0) << k;  // winding kept, no flipped or empty triangle
      tri_area += signed_area;
    }
    EXPECT_NEAR(tri_area, poly_area, 1e-9 * std::abs(poly_area) + 1e-12) << k;
    // Points off the boundary lie in one triangle iff inside the polygon.
    Point2 lo = outline[0], hi = outline[0];
    for (const Point2& p : outline) {
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    }
    for (int i = 0; i < 300; ++i) {
      const double x = lo.x + (hi.x - lo.x) * s.uniform(-0.1f, 1.1f), y = lo.y + (hi.y - lo.y) * s.uniform(-0.1f, 1.1f);
      if (boundary_distance(outline, x, y) < 1e-9) continue;
      int covering = 0;
      for (const auto& t : tris) {
        std::vector<Point2> tp{{t[0].x, t[0].y}, {t[1].x, t[1].y}, {t[2].x, t[2].y}};
        covering += winding_number(tp, x, y) != 0;
      }
      ASSERT_EQ(covering, winding_number(outline, x, y) != 0 ? 1 : 0) << k << ": " << x << ", " << y;
    }
  }
  EXPECT_TRUE(triangulate_polygon({{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}}).empty());
}

// Random star-shaped polygons (5..40 vertices, mostly concave) in random
// planes around the origin, and one far from it.
std::vector<PolygonDesc> random_polygon_descs(RaySampler& s, std::size_t n, int min_vertices = 5,
                                              int max_vertices = 40) {
  std::vector<PolygonDesc> descs;
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3<float> normal = s.unit_direction();
    const Vec3<float> e1 = normalize(cross(normal, std::abs(normal.x) < 0.9f ? Vec3<float>{1, 0, 0} : Vec3<float>{0, 1, 0}));
    const Vec3<float> e2 = cross(normal, e1);
    const Vec3<float> center = k == 0 ? Vec3<float>{300, -200, 100} : s.in_box({-4, -4, -4}, {4, 4, 4});
    const float radius = s.uniform(0.5f, 2.f);
    const bool convex = k % 4 == 1;
    const int count = s.uniform_int(min_vertices, max_vertices);
    PolygonDesc d;
    for (int i = 0; i < count; ++i) {
      const float a = 6.2831853f * float(i) / float(count);
      const float r = radius * (convex ? 1.f : s.uniform(0.3f, 1.f));
      d.vertices.push_back(center + e1 * (r * std::cos(a)) + e2 * (r * std::sin(a)));
    }
    descs.push_back(d);
  }
  return descs;
}

Vec3<float> polygon_point(const PolygonDesc& d, RaySampler& s) {
  // A point of a fan triangle (vertex 0, i, i + 1): inside the hull at least.
  const int i = s.uniform_int(1, int(d.vertices.size()) - 2);
  float a = s.uniform(0, 1), b = s.uniform(0, 1);
  if (a + b > 1) a = 1 - a, b = 1 - b;
  const Vec3<float>& v0 = d.vertices[0];
  return v0 + (d.vertices[i] - v0) * a + (d.vertices[i + 1] - v0) * b;
}

// The polygon's plane in double: unit Newell normal and centroid.
struct PlaneD {
  double n[3], c[3];
  int drop;
};
PlaneD plane_of(const PolygonDesc& d) {
  PlaneD p{{0, 0, 0}, {0, 0, 0}, 2};
  const std::size_t m = d.vertices.size();
  for (std::size_t i = 0; i < m; ++i) {
    const Vec3<float>& a = d.vertices[i];
    const Vec3<float>& b = d.vertices[(i + 1) % m];
    p.n[0] += (double(a.y) - b.y) * (double(a.z) + b.z);
    p.n[1] += (double(a.z) - b.z) * (double(a.x) + b.x);
    p.n[2] += (double(a.x) - b.x) * (double(a.y) + b.y);
    for (int k = 0; k < 3; ++k) p.c[k] += double(a[k]) / double(m);
  }
  const double len = std::sqrt(p.n[0] * p.n[0] + p.n[1] * p.n[1] + p.n[2] * p.n[2]);
  for (double& x : p.n) x /= len;
  const double ax = std::abs(p.n[0]), ay = std::abs(p.n[1]), az = std::abs(p.n[2]);
  p.drop = (ax >= ay && ax >= az) ? 0 : (ay >= az ? 1 : 2);
  return p;
}

// Every ray against one polygon, by the crossing kernel and by its ear-clipped
// triangles through the watertight kernel: hit/miss may differ only near the
// polygon's boundary. The distance that counts is measured in double on the
// fitted plane, in units of the float spacing at the scene's scale
// (2^-24 max|coordinate|), times the cosine of the incidence angle (a grazing
// ray turns the float vertices' tiny distance from one plane into a large
// shift along it).
TEST(PolygonStability, AgreesWithWatertightTriangulation) {
  RaySampler s(29);
  std::vector<PolygonDesc> descs = random_polygon_descs(s, 13);
  descs.push_back(in_plane(l_shape(), 0.5f, 0.25f, 0.f));
  descs.push_back(in_plane(comb(), -1.f, 0.f, 0.125f));
  descs.push_back(in_plane(star(), 2.f));
  std::size_t rays_total = 0, hits_total = 0, aimed_at_boundary = 0, disagree = 0, disagree_aimed = 0;
  double worst_ulps = 0, worst_t = 0, worst_t_far = 0;
  std::size_t polygon_wrong = 0, triangles_wrong = 0;
  double worst_polygon_ulps = 0, worst_triangles_ulps = 0;
  for (const PolygonDesc& desc : descs) {
    const bool far = &desc == &descs[0];  // centred at (300, -200, 100)
    const PolygonSoA polygon = polygons_of({desc});
    ASSERT_EQ(polygon.size(), 1u);
    std::vector<TriangleDesc> tri_descs;
    for (const auto& t : triangulate_polygon(desc)) tri_descs.push_back({t, std::nullopt, std::nullopt});
    BuildReport tri_report;
    const TriangleSoA triangles = build_triangles(tri_descs, tri_report);
    ASSERT_EQ(tri_report.dropped(), 0u);
    // Rays toward the polygon's hull, and exactly toward its vertices and edges.
    Vec3<float> lo = desc.vertices[0], hi = desc.vertices[0];
    for (const Vec3<float>& v : desc.vertices) {
      lo = {std::min(lo.x, v.x), std::min(lo.y, v.y), std::min(lo.z, v.z)};
      hi = {std::max(hi.x, v.x), std::max(hi.y, v.y), std::max(hi.z, v.z)};
    }
    const float extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    const Vec3<float> mid = (lo + hi) * 0.5f, reach = (hi - lo) * 0.6f;
    std::vector<Ray<float>> rays;
    for (int i = 0; i < 9'000; ++i) {
      Vec3<float> target;
      if (i % 3 == 0) {
        const std::size_t k = std::size_t(s.uniform_int(0, int(desc.vertices.size()) - 1));
        const Vec3<float> a = desc.vertices[k], b = desc.vertices[(k + 1) % desc.vertices.size()];
        target = i % 2 ? a : a + (b - a) * s.uniform(0, 1);
      } else {
        target = s.in_box(mid - reach, mid + reach);
      }
      rays.push_back(s.toward(target + s.unit_direction() * (3 * extent), target));
    }
    const RaySoA soa = testing::to_soa(rays);
    HitSoA by_polygon(soa), by_triangles(soa);
    study_polygon_streams<KernelUnit::scalar>(PolygonMethod::crossing).closest_packets(soa, polygon, by_polygon);
    study_triangle_streams<KernelUnit::scalar>(TriangleMethod::watertight)
        .closest_packets(soa, triangles, by_triangles);
    // The outline projected like the kernel (drop the dominant axis).
    const PlaneD plane = plane_of(desc);
    const int au = (plane.drop + 1) % 3, av = (plane.drop + 2) % 3;
    std::vector<Point2> outline;
    for (const Vec3<float>& v : desc.vertices) outline.push_back({double(v[au]), double(v[av])});
    for (std::size_t r = 0; r < rays.size(); ++r) {
      const Ray<float>& ray = rays[r];
      const bool p_hit = by_polygon.id[r] != kNoHit, t_hit = by_triangles.id[r] != kNoHit;
      hits_total += p_hit;
      // Double hit point on the fitted plane, its distance to the boundary, the incidence.
      double num = 0, den = 0, dir2 = 0, scale = 0;
      for (int k = 0; k < 3; ++k) {
        num += plane.n[k] * (plane.c[k] - double(ray.origin[k]));
        den += plane.n[k] * double(ray.direction[k]);
        dir2 += double(ray.direction[k]) * ray.direction[k];
        scale = std::max({scale, std::abs(double(ray.origin[k])), std::abs(double(lo[k])), std::abs(double(hi[k]))});
      }
      const double t = num / den, cosine = std::abs(den) / std::sqrt(dir2);
      const double x = double(ray.origin[au]) + t * ray.direction[au], y = double(ray.origin[av]) + t * ray.direction[av];
      const double ulps = boundary_distance(outline, x, y) * cosine / (scale * 0x1p-24);
      const bool exact = t > 0 && winding_number(outline, x, y) != 0;  // double reference
      if (p_hit != exact) {
        ++polygon_wrong;
        worst_polygon_ulps = std::max(worst_polygon_ulps, ulps);
      }
      if (t_hit != exact) {
        ++triangles_wrong;
        worst_triangles_ulps = std::max(worst_triangles_ulps, ulps);
      }
      const bool aimed = r % 3 == 0;
      aimed_at_boundary += aimed;
      if (p_hit && t_hit && cosine > 0.1) {
        double& worst = far ? worst_t_far : worst_t;
        worst = std::max(worst, std::abs(double(by_polygon.t[r]) - by_triangles.t[r]) / by_triangles.t[r]);
      }
      if (p_hit == t_hit) continue;
      ++disagree;
      disagree_aimed += aimed;
      worst_ulps = std::max(worst_ulps, ulps);
    }
    rays_total += rays.size();
  }
  std::printf("[ measured ] polygon vs triangulated watertight: %zu rays (%zu aimed exactly at vertices/edges), %zu "
              "polygon hits; %zu disagree (%zu of them aimed), all within %.3g float spacings x cos(incidence) of the "
              "boundary; hit t relative difference (cos > 0.1) <= %.3g near the origin, %.3g for the polygon 370 away\n",
              rays_total, aimed_at_boundary, hits_total, disagree, disagree_aimed, worst_ulps, worst_t, worst_t_far);
  std::printf("[ measured ] against the double reference (winding number at the double hit point): crossing wrong "
              "on %zu rays, within %.3g spacings; triangulated on %zu, within %.3g spacings\n",
              polygon_wrong, worst_polygon_ulps, triangles_wrong, worst_triangles_ulps);
  EXPECT_LT(worst_polygon_ulps, 16);
  EXPECT_GT(hits_total, rays_total / 3);
  EXPECT_LT(disagree - disagree_aimed, rays_total / 1000);  // random rays rarely land that close
  EXPECT_LT(worst_ulps, 16);
  // t = -(d + n.o) / (n.dir) cancels when |o| and |d| dwarf the distance to the plane.
  EXPECT_LT(worst_t, 5e-5);
  EXPECT_LT(worst_t_far, 5e-4);
}

// ---- edge bands ---------------------------------------------------------------

// A gear of 36 teeth (144 vertices, like SPD gears' faces) in the z = 0.5 plane.
std::vector<Point2> gear() {
  std::vector<Point2> p;
  for (int tooth = 0; tooth < 36; ++tooth) {
    const double a = tooth * std::numbers::pi / 18;
    for (const auto& [r, da] : {std::pair{1.6, 0.0}, {2.0, 0.02}, {2.0, 0.06}, {1.6, 0.08}}) {
      p.push_back({double(float(r * std::cos(a + da))), double(float(r * std::sin(a + da)))});
    }
  }
  return p;
}

// Polygons with edge bands: the comb (horizontal edges sharing scan lines),
// the gear, and random concave polygons of 32 to 300 vertices.
std::vector<PolygonDesc> banded_polygon_descs(RaySampler& s) {
  std::vector<PolygonDesc> descs{in_plane(comb(), 1.f, 0.01f, 0.02f), in_plane(gear(), 0.5f)};
  for (PolygonDesc& d : random_polygon_descs(s, 9, 32, 300)) descs.push_back(std::move(d));
  return descs;
}

TEST(PolygonBuild, EdgeBandsListEveryEdgeTheirRangeMeets) {
  RaySampler s(29);
  std::vector<PolygonDesc> descs = banded_polygon_descs(s);
  // Every edge spans the whole v range: the band count must shrink to bound the lists.
  PolygonDesc zigzag;
  for (int i = 0; i < 64; ++i) zigzag.vertices.push_back({float(i) * 0.1f, i % 2 ? 1.f : 0.f, 0.f});
  zigzag.vertices.push_back({6.3f, -1.f, 0.f});
  zigzag.vertices.push_back({0.f, -1.f, 0.f});
  descs.push_back(zigzag);
  descs.push_back(in_plane(star()));  // 10 vertices: no bands
  const PolygonSoA soa = polygons_of(descs);
  ASSERT_EQ(soa.size(), descs.size());
  for (std::size_t i = 0; i < soa.size(); ++i) {
    SCOPED_TRACE(i);
    const std::size_t n = std::size_t(soa.vertex_count[i]);
    const int bands = soa.band_count[i];
    if (n < kMinBandedVertices) {
      EXPECT_EQ(bands, 0);
      continue;
    }
    ASSERT_GE(bands, 2);
    EXPECT_LE(std::size_t(bands), std::min(kMaxEdgeBands, n / kEdgesPerBand));
    const std::size_t* first = soa.band_first.data() + soa.band_start[i];
    EXPECT_LE(first[bands] - first[0], kMaxBandRefsPerEdge * n);
    const float* pv = soa.pv.data() + soa.first_vertex[i];
    for (int band = 0; band < bands; ++band) {
      std::vector<bool> listed(n, false);
      for (std::size_t e = first[band]; e < first[band + 1]; ++e) listed[soa.band_edges[e]] = true;
      for (std::size_t k = 0; k < n; ++k) {
        const float a = pv[k == 0 ? n - 1 : k - 1], b = pv[k];
        const int lo = polygon_detail::band_of(std::min(a, b), soa.vmin[i], soa.band_scale[i], bands);
        const int hi = polygon_detail::band_of(std::max(a, b), soa.vmin[i], soa.band_scale[i], bands);
        EXPECT_EQ(listed[k], lo <= band && band <= hi) << "band " << band << " edge " << k;
      }
    }
  }
  EXPECT_LE(soa.band_count[descs.size() - 2], 4);  // the zigzag: at most 4 bands of 64 edges each
}

// What a store holds counts every column and list, named one by one here:
// the per-polygon and per-vertex columns, the band lists and spans, the source.
TEST(PolygonBuild, AStoresBytesCountEveryColumnBandListAndTheSource) {
  RaySampler s(37);
  const PolygonSoA soa = polygons_of(banded_polygon_descs(s));
  ASSERT_GT(soa.band_spans.size(), 0u);
  ASSERT_GT(soa.band_edges.size(), 0u);
  std::size_t held = 0;
  for (const AlignedFloats* c : {&soa.nx, &soa.ny, &soa.nz, &soa.origin_u, &soa.origin_v, &soa.umin, &soa.umax,
                                 &soa.vmin, &soa.vmax, &soa.reach, &soa.plane_slack, &soa.band_scale, &soa.pu, &soa.pv,
                                 &soa.px, &soa.py, &soa.pz}) {
    held += bytes_of(*c);
  }
  for (const AlignedInts* c : {&soa.axis_u, &soa.axis_v, &soa.vertex_count, &soa.band_count}) held += bytes_of(*c);
  for (const std::vector<std::size_t>* c : {&soa.first_vertex, &soa.band_start, &soa.band_first}) {
    held += c->capacity() * sizeof(std::size_t);
  }
  held += soa.band_edges.capacity() * sizeof(std::uint32_t) + soa.band_spans.capacity() * sizeof(BandSpan) +
          soa.source.capacity() * sizeof(std::uint32_t);
  EXPECT_EQ(soa.memory_bytes(), held);
}

// Each band's span lies the margin clear of every edge it lists, and a
// point it decides has the crossing rule's answer (in double, on the stored
// projected vertices): inside within the inside range, outside beyond the
// edges' range.
TEST(PolygonBuild, BandSpansLieClearOfTheirEdgesAndDecideRightly) {
  RaySampler s(31);
  const std::vector<PolygonDesc> descs = banded_polygon_descs(s);
  const PolygonSoA soa = polygons_of(descs);
  ASSERT_EQ(soa.size(), descs.size());
  std::size_t bands_total = 0, inside_ranges = 0, points = 0;
  for (std::size_t i = 0; i < soa.size(); ++i) {
    SCOPED_TRACE(i);
    const std::size_t n = std::size_t(soa.vertex_count[i]);
    const int bands = soa.band_count[i];
    ASSERT_GE(bands, 2);
    const float* pu = soa.pu.data() + soa.first_vertex[i];
    const float* pv = soa.pv.data() + soa.first_vertex[i];
    std::vector<Point2> outline;
    for (std::size_t k = 0; k < n; ++k) outline.push_back({pu[k], pv[k]});
    const double clearance = 0.99 * double(kBandSpanMargin) * (double(soa.umax[i]) - double(soa.umin[i]));
    const std::size_t* first = soa.band_first.data() + soa.band_start[i];
    const BandSpan* spans = soa.band_spans.data() + soa.band_start[i];
    int inside_bands = 0;
    for (int band = 0; band < bands; ++band) {
      SCOPED_TRACE(band);
      const BandSpan& span = spans[band];
      const bool has_inside = span.inside_lo < span.inside_hi;
      for (std::size_t e = first[band]; e < first[band + 1]; ++e) {
        const std::size_t k = soa.band_edges[e], j = k == 0 ? n - 1 : k - 1;
        const double lo = std::min(pu[j], pu[k]), hi = std::max(pu[j], pu[k]);
        EXPECT_LE(span.edges_lo, lo - clearance) << "edge " << k;
        EXPECT_GE(span.edges_hi, hi + clearance) << "edge " << k;
        if (has_inside) {
          EXPECT_TRUE(hi <= span.inside_lo - clearance || lo >= span.inside_hi + clearance) << "edge " << k;
        }
      }
      ++bands_total;
      inside_ranges += has_inside;
      inside_bands += has_inside;
      // Scan lines of this band (band_of maps them to it), through the span's bounds.
      for (int step = 0; step < 8; ++step) {
        const float v = soa.vmin[i] + (float(band) + (float(step) + 0.5f) / 8.f) / soa.band_scale[i];
        if (polygon_detail::band_of(v, soa.vmin[i], soa.band_scale[i], bands) != band) continue;
        const float left = std::nextafter(span.edges_lo, -kInf), right = std::nextafter(span.edges_hi, kInf);
        EXPECT_FALSE(crossing_reference(outline, left, v)) << v;
        EXPECT_FALSE(crossing_reference(outline, right, v)) << v;
        points += 2;
        if (!has_inside) continue;
        for (const float u : {std::nextafter(span.inside_lo, kInf), std::nextafter(span.inside_hi, -kInf),
                              0.5f * (span.inside_lo + span.inside_hi)}) {
          EXPECT_TRUE(crossing_reference(outline, u, v)) << u << " " << v;
          ++points;
        }
      }
    }
    if (i == 1) {
      EXPECT_GE(inside_bands, bands / 2);  // the gear: an inside range in most bands
    }
  }
  std::printf("[ measured ] %zu bands, %zu with an inside range; %zu points checked against the crossing rule\n",
              bands_total, inside_ranges, points);
  EXPECT_GT(inside_ranges, bands_total / 4);
}

template <class W>
class PolygonWidths : public testing::UnitTest<W> {};
TYPED_TEST_SUITE(PolygonWidths, testing::KernelUnits);

TYPED_TEST(PolygonWidths, MatchesScalarBitForBit) {
  RaySampler s(17);
  const std::vector<PolygonDesc> descs = random_polygon_descs(s, 13);  // not a multiple of any width
  BuildReport report;
  const PolygonSoA polygons = build_polygons(descs, report);
  ASSERT_EQ(polygons.size(), 13u);
  std::vector<Ray<float>> rays = testing::adversarial_rays(s, 40'003, {0, 0, 0}, 4.f);
  for (int i = 0; i < 50'000; ++i) {
    const PolygonDesc& d = descs[std::size_t(s.uniform_int(1, 12))];
    rays.push_back(s.toward(s.in_box({-9, -9, -9}, {9, 9, 9}), polygon_point(d, s)));
  }
  for (int i = 0; i < 12'000; ++i) {  // through vertices and edge midpoints, and grazing
    const PolygonDesc& d = descs[std::size_t(s.uniform_int(0, 12))];
    const std::size_t k = std::size_t(s.uniform_int(0, int(d.vertices.size()) - 1));
    const Vec3<float> a = d.vertices[k], b = d.vertices[(k + 1) % d.vertices.size()];
    const Vec3<float> target = i % 3 == 0 ? a : (i % 3 == 1 ? (a + b) * 0.5f : a);
    Ray<float> r = s.toward(target + s.unit_direction() * 5.f, target);
    if (i % 3 == 2) r = {target - (b - a), (b - a) + s.unit_direction() * s.uniform(-1e-6f, 1e-6f), 0.f, kInf};
    rays.push_back(r);
  }
  RaySoA soa = testing::to_soa(rays);
  ASSERT_NE(soa.count % 8, 0u);
  testing::poison_padding(soa);
  const auto ref = testing::expect_streams_match_scalar(
      study_polygon_streams<KernelUnit::scalar>(PolygonMethod::crossing),
      study_polygon_streams<TestFixture::kUnit>(PolygonMethod::crossing), soa, polygons);
  EXPECT_GT(ref.closest_packets.hit_count(), rays.size() / 3);  // the test exercises hits
}

// The band spans decide only lanes clear of every edge by their margin, so
// every result equals the ray-space loop's over all edges (band_count 0)
// bit for bit, at every width, in both orientations.
TYPED_TEST(PolygonWidths, EdgeBandsGiveTheFullLoopsBits) {
  RaySampler s(23);
  const std::vector<PolygonDesc> descs = banded_polygon_descs(s);
  const PolygonSoA banded = polygons_of(descs);
  ASSERT_EQ(banded.size(), descs.size());
  for (std::size_t i = 0; i < banded.size(); ++i) ASSERT_GE(banded.band_count[i], 2) << i;
  PolygonSoA plain = banded;
  std::fill(plain.band_count.begin(), plain.band_count.end(), 0);
  std::vector<Ray<float>> rays = testing::adversarial_rays(s, 20'003, {0, 0, 0}, 4.f);
  for (int i = 0; i < 60'000; ++i) {
    const PolygonDesc& d = descs[std::size_t(s.uniform_int(0, int(descs.size()) - 1))];
    rays.push_back(s.toward(s.in_box({-9, -9, -9}, {9, 9, 9}) + Vec3<float>{50, 3, 0}, polygon_point(d, s)));
  }
  for (int i = 0; i < 20'000; ++i) {  // through vertices (their scan lines), edge midpoints, and grazing
    const PolygonDesc& d = descs[std::size_t(s.uniform_int(0, int(descs.size()) - 1))];
    const std::size_t k = std::size_t(s.uniform_int(0, int(d.vertices.size()) - 1));
    const Vec3<float> a = d.vertices[k], b = d.vertices[(k + 1) % d.vertices.size()];
    const Vec3<float> target = i % 3 == 1 ? (a + b) * 0.5f : a;
    Ray<float> r = s.toward(target + s.unit_direction() * 5.f, target);
    if (i % 3 == 2) r = {target - (b - a), (b - a) + s.unit_direction() * s.uniform(-1e-6f, 1e-6f), 0.f, kInf};
    rays.push_back(r);
  }
  for (int i = 0; i < 4'000; ++i) {  // straight down on the comb's grid of scan lines through its vertices
    const Vec3<float> origin{0.5f * float(s.uniform_int(-2, 200)), 0.5f * float(s.uniform_int(-1, 12)), 100.f};
    rays.push_back({origin, {0, 0, -1}, 0.f, kInf});
  }
  // Straight down on the comb and the gear (their u, v are x, y) within a few
  // floats of a band span's bounds, where the spans stop deciding.
  for (std::size_t i = 0; i < 2; ++i) {
    ASSERT_EQ(banded.axis_u[i], 0);
    const BandSpan* spans = banded.band_spans.data() + banded.band_start[i];
    for (int band = 0; band < banded.band_count[i]; ++band) {
      for (int k = 0; k < 24; ++k) {
        const BandSpan& span = spans[band];
        const float bound = std::array{span.edges_lo, span.inside_lo, span.inside_hi, span.edges_hi}[k % 4];
        float u = bound;
        for (int step = s.uniform_int(-3, 3); step != 0; step += step < 0 ? 1 : -1) {
          u = std::nextafter(u, step < 0 ? -kInf : kInf);
        }
        const float v = banded.vmin[i] + (float(band) + s.uniform(0.f, 1.f)) / banded.band_scale[i];
        rays.push_back({{banded.origin_u[i] + u, banded.origin_v[i] + v, 100.f}, {0, 0, -1}, 0.f, kInf});
      }
    }
  }
  RaySoA soa = testing::to_soa(rays);
  testing::poison_padding(soa);
  const testing::StreamResults ref =
      testing::run_streams(study_polygon_streams<KernelUnit::scalar>(PolygonMethod::crossing), soa, plain);
  testing::expect_results_match_scalar(
      ref, testing::run_streams(study_polygon_streams<TestFixture::kUnit>(PolygonMethod::crossing), soa, banded));
  EXPECT_GT(ref.closest_packets.hit_count(), rays.size() / 4);  // the test exercises hits
}

}  // namespace
}  // namespace quiver
