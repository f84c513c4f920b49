#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "geometry/bvh_store.h"
#include "geometry/kind_streams.h"
#include "tests/support/kernel_checks.h"
#include "tests/support/ray_sampling.h"
#include "tests/support/study_streams.h"

namespace quiver {
namespace {

using testing::RaySampler;
using Face = std::array<std::uint32_t, 3>;

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr TriangleMethod kMethods[] = {TriangleMethod::moller_trumbore, TriangleMethod::watertight};

const char* method_name(TriangleMethod m) {
  return m == TriangleMethod::moller_trumbore ? "moller_trumbore" : "watertight";
}

TriangleSoA triangles_of(const std::vector<TriangleDesc>& descs, BuildReport* out = nullptr) {
  BuildReport report;
  TriangleSoA soa = build_triangles(descs, report);
  if (out) *out = report;
  return soa;
}

TriangleDesc tri(const Vec3<float>& a, const Vec3<float>& b, const Vec3<float>& c) { return {{a, b, c}, {}, {}}; }

Hit<float> closest(TriangleMethod m, const Ray<float>& ray, const TriangleSoA& tris) {
  return testing::closest_hit(study_triangle_streams<KernelUnit::scalar>(m), ray, tris);
}

// The widest streams this CPU runs (equal to scalar bit for bit, tested below).
KernelStreams<TriangleSoA> fastest_streams(TriangleMethod m) {
  return with_kernel_unit(kernel_unit_for(best_supported_isa()),
                          [&](auto u) { return study_triangle_streams<decltype(u)::value>(m); });
}

Vec3<float> on_triangle(const std::array<Vec3<float>, 3>& p, float u, float v) {
  return p[0] * (1.f - u - v) + p[1] * u + p[2] * v;
}

Vec3<double> to_double(const Vec3<float>& v) { return {v.x, v.y, v.z}; }

// Moller-Trumbore in double on the float inputs: the reference t, u, v.
struct Reference {
  bool hit = false;
  double t = 0, u = 0, v = 0;
};
Reference reference(const Ray<float>& ray, const std::array<Vec3<float>, 3>& p) {
  const Vec3<double> o = to_double(ray.origin), d = to_double(ray.direction);
  const Vec3<double> v0 = to_double(p[0]), e1 = to_double(p[1]) - v0, e2 = to_double(p[2]) - v0;
  const Vec3<double> pv = cross(d, e2);
  const double det = dot(e1, pv);
  Reference r;
  if (det == 0 || !std::isfinite(det)) return r;
  const Vec3<double> offset = o - v0, q = cross(offset, e1);
  r.u = dot(offset, pv) / det;
  r.v = dot(d, q) / det;
  r.t = dot(e2, q) / det;
  r.hit = r.u >= 0 && r.v >= 0 && r.u + r.v <= 1 && r.t > ray.tmin && r.t < ray.tmax;
  return r;
}

// ---- meshes -------------------------------------------------------------

struct Mesh {
  std::vector<Vec3<float>> positions;
  std::vector<Face> faces;

  std::vector<TriangleDesc> triangles() const { return triangles_from_indexed(positions, faces); }
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges() const {
    std::set<std::pair<std::uint32_t, std::uint32_t>> e;
    for (const Face& f : faces) {
      for (int k = 0; k < 3; ++k) e.insert(std::minmax(f[k], f[(k + 1) % 3]));
    }
    return e;
  }
  // Closed: every directed edge appears once and its reverse once.
  bool closed() const {
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
    for (const Face& f : faces) {
      for (int k = 0; k < 3; ++k) ++directed[{f[k], f[(k + 1) % 3]}];
    }
    for (const auto& [edge, n] : directed) {
      if (n != 1) return false;
      const auto back = directed.find({edge.second, edge.first});
      if (back == directed.end() || back->second != 1) return false;
    }
    return true;
  }
};

Vec3<float> unit(const Vec3<float>& v) {
  const Vec3<double> d = to_double(v);
  const double len = std::sqrt(dot(d, d));
  return {float(d.x / len), float(d.y / len), float(d.z / len)};
}

// Unit icosahedron subdivided `levels` times, midpoints pushed to the sphere.
Mesh icosphere(int levels) {
  const float g = 1.6180339887f;
  Mesh m;
  for (const Vec3<float>& v : std::initializer_list<Vec3<float>>{
           {-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
           {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}}) {
    m.positions.push_back(unit(v));
  }
  m.faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
             {11, 10, 2}, {10, 7, 6}, {7, 1, 8},   {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
             {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      const auto found = midpoints.find(key);
      if (found != midpoints.end()) return found->second;
      m.positions.push_back(unit((m.positions[a] + m.positions[b]) * 0.5f));
      const auto index = static_cast<std::uint32_t>(m.positions.size() - 1);
      midpoints[key] = index;
      return index;
    };
    std::vector<Face> finer;
    for (const Face& f : m.faces) {
      const std::uint32_t ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
      finer.insert(finer.end(), {{f[0], ab, ca}, {f[1], bc, ab}, {f[2], ca, bc}, {ab, bc, ca}});
    }
    m.faces = std::move(finer);
  }
  return m;
}

// Axis-aligned cube [-1, 1]^3, two triangles per face.
Mesh cube() {
  Mesh m;
  for (int i = 0; i < 8; ++i) m.positions.push_back({i & 1 ? 1.f : -1.f, i & 2 ? 1.f : -1.f, i & 4 ? 1.f : -1.f});
  const std::array<std::uint32_t, 4> quads[6] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                                 {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.faces.push_back({q[0], q[1], q[2]});
    m.faces.push_back({q[0], q[2], q[3]});
  }
  return m;
}

// A closed, star-shaped polyhedron with arbitrary float coordinates: an
// icosphere with each vertex pushed radially by a random factor, scaled
// unevenly and moved off the origin.
Mesh jittered_polyhedron(RaySampler& s, const Vec3<float>& center) {
  Mesh m = icosphere(2);
  for (Vec3<float>& p : m.positions) {
    const float r = s.uniform(0.85f, 1.15f);
    p = Vec3<float>{p.x * r * 2.7182817f, p.y * r * 1.4142135f, p.z * r * 3.3166247f} + center;
  }
  return m;
}

// ---- analytic cases ----------------------------------------------------------

TEST(TriangleKernel, HitsUnitTriangleWithHandComputedTuvAndNormal) {
  const TriangleSoA t = triangles_of({tri({0, 0, 0}, {1, 0, 0}, {0, 1, 0})});
  for (TriangleMethod m : kMethods) {
    SCOPED_TRACE(method_name(m));
    const Hit<float> h = closest(m, {{0.25f, 0.5f, 2}, {0, 0, -1}, 0.f, kInf}, t);
    ASSERT_EQ(h.id, 0);
    EXPECT_FLOAT_EQ(h.t, 2.f);
    EXPECT_FLOAT_EQ(h.u, 0.25f);  // weight of v1
    EXPECT_FLOAT_EQ(h.v, 0.5f);   // weight of v2
    EXPECT_FLOAT_EQ(h.ng.x, 0.f);
    EXPECT_FLOAT_EQ(h.ng.y, 0.f);
    EXPECT_FLOAT_EQ(h.ng.z, 1.f);  // (v1-v0) x (v2-v0)
  }
}

TEST(TriangleKernel, HitsSlantedTriangleThroughItsCentroid) {
  // Plane x + y + z = 2; the ray along (1,1,1) meets it at (2/3, 2/3, 2/3).
  const TriangleSoA t = triangles_of({tri({2, 0, 0}, {0, 2, 0}, {0, 0, 2})});
  for (TriangleMethod m : kMethods) {
    SCOPED_TRACE(method_name(m));
    const Hit<float> h = closest(m, {{0, 0, 0}, {1, 1, 1}, 0.f, kInf}, t);
    ASSERT_EQ(h.id, 0);
    EXPECT_NEAR(h.t, 2.f / 3.f, 1e-6f);
    EXPECT_NEAR(h.u, 1.f / 3.f, 1e-6f);
    EXPECT_NEAR(h.v, 1.f / 3.f, 1e-6f);
    EXPECT_FLOAT_EQ(h.ng.x, 4.f);  // (-2,2,0) x (-2,0,2)
    EXPECT_FLOAT_EQ(h.ng.y, 4.f);
    EXPECT_FLOAT_EQ(h.ng.z, 4.f);
  }
}

TEST(TriangleKernel, TwoSidedAndNormalNotFlipped) {
  const TriangleSoA t = triangles_of({tri({0, 0, 0}, {1, 0, 0}, {0, 1, 0})});
  for (TriangleMethod m : kMethods) {
    SCOPED_TRACE(method_name(m));
    const Hit<float> h = closest(m, {{0.25f, 0.25f, -2}, {0, 0, 4}, 0.f, kInf}, t);
    ASSERT_EQ(h.id, 0);
    EXPECT_FLOAT_EQ(h.t, 0.5f);  // direction not normalised: t in its units
    EXPECT_FLOAT_EQ(h.ng.z, 1.f);
    // x, y or z dominant, either sign (every watertight permutation).
    const Vec3<float> target{0.2f, 0.3f, 0.f};
    for (const Vec3<float>& dir : std::initializer_list<Vec3<float>>{{4, 1, 1}, {1, 4, 1}, {1, 1, 4}}) {
      for (float sign : {1.f, -1.f}) {
        const Vec3<float> d = dir * sign;
        const Hit<float> g = closest(m, {target - d * 3.f, d, 0.f, kInf}, t);
        SCOPED_TRACE(::testing::Message() << "d = " << d.x << ", " << d.y << ", " << d.z);
        ASSERT_EQ(g.id, 0);
        EXPECT_NEAR(g.t, 3.f, 1e-5f);
        EXPECT_NEAR(g.u, 0.2f, 1e-5f);
        EXPECT_NEAR(g.v, 0.3f, 1e-5f);
      }
    }
  }
}

TEST(TriangleKernel, EdgesAndVerticesAreInside) {
  const TriangleSoA t = triangles_of({tri({0, 0, 0}, {1, 0, 0}, {0, 1, 0})});
  for (TriangleMethod m : kMethods) {
    SCOPED_TRACE(method_name(m));
    for (const Vec3<float>& p : std::initializer_list<Vec3<float>>{
             {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5f, 0, 0}, {0, 0.5f, 0}, {0.5f, 0.5f, 0}}) {
      EXPECT_EQ(closest(m, {{p.x, p.y, 1}, {0, 0, -1}, 0.f, kInf}, t).id, 0) << p.x << ", " << p.y;
    }
    EXPECT_EQ(closest(m, {{0.5f, 0.5001f, 1}, {0, 0, -1}, 0.f, kInf}, t).id, kNoHit);
    EXPECT_EQ(closest(m, {{-0.0001f, 0.5f, 1}, {0, 0, -1}, 0.f, kInf}, t).id, kNoHit);
  }
}

TEST(TriangleKernel, RespectsOpenIntervalAndMissesParallelAndZeroRays) {
  const TriangleSoA t = triangles_of({tri({0, 0, 0}, {1, 0, 0}, {0, 1, 0})});
  for (TriangleMethod m : kMethods) {
    SCOPED_TRACE(method_name(m));
    EXPECT_EQ(closest(m, {{0.2f, 0.2f, 1}, {0, 0, -1}, 0.f, 1.f}, t).id, kNoHit);   // t == tmax
    EXPECT_EQ(closest(m, {{0.2f, 0.2f, 1}, {0, 0, -1}, 1.f, 5.f}, t).id, kNoHit);   // t == tmin
    EXPECT_EQ(closest(m, {{0.2f, 0.2f, 1}, {0, 0, 1}, 0.f, kInf}, t).id, kNoHit);   // behind
    EXPECT_EQ(closest(m, {{0.2f, 0.2f, 1}, {0, 0, 1}, -5.f, kInf}, t).id, 0);       // behind, tmin < t
    EXPECT_EQ(closest(m, {{0.2f, 0.2f, 0}, {0, 0, -1}, 0.f, kInf}, t).id, kNoHit);  // origin on it: t = 0
    EXPECT_EQ(closest(m, {{-1, 0.25f, 0}, {1, 0, 0}, -kInf, kInf}, t).id, kNoHit);  // in the plane
    EXPECT_EQ(closest(m, {{-1, 0.25f, 1}, {1, 0, 0}, -kInf, kInf}, t).id, kNoHit);  // parallel above
    EXPECT_EQ(closest(m, {{0.2f, 0.2f, 1}, {0, 0, 0}, -kInf, kInf}, t).id, kNoHit); // zero direction
  }
}

TEST(TriangleKernel, ClosestOfSeveralAndTieGoesToFirst) {
  const TriangleSoA t = triangles_of({tri({0, 0, 0}, {1, 0, 0}, {0, 1, 0}), tri({0, 0, 1}, {1, 0, 1}, {0, 1, 1}),
                                      tri({0, 0, 1}, {0, 1, 1}, {1, 0, 1})});
  for (TriangleMethod m : kMethods) {
    SCOPED_TRACE(method_name(m));
    const Hit<float> h = closest(m, {{0.25f, 0.25f, 5}, {0, 0, -1}, 0.f, kInf}, t);
    EXPECT_EQ(h.id, 1);
    EXPECT_FLOAT_EQ(h.t, 4.f);
    EXPECT_FLOAT_EQ(h.u, 0.25f);
  }
}

TEST(TriangleKernel, WatertightResolvesAnEdgeFunctionThatRoundsToZero) {
  // Ray along +z from the origin; the shared edge BC passes 2e-8 from it.
  // In float cx*by and cy*bx round to the same 1 + 2^-11, so w0 == 0 and both
  // triangles would count the origin as on the edge; exactly it is -2^-24 for
  // (A, B, C): the origin lies on exactly one side, and only that triangle hits.
  const float e = std::ldexp(1.f, -12);
  const Vec3<float> b{1, 1 + e, 1}, c{-(1 + e), -(1 + 2 * e), 1};
  const std::array<Vec3<float>, 3> t1{Vec3<float>{-2, 2, 1}, b, c}, t2{Vec3<float>{2, -2, 1}, c, b};
  const Ray<float> ray{{0, 0, 0}, {0, 0, 1}, 0.f, kInf};
  const bool ref1 = reference(ray, t1).hit, ref2 = reference(ray, t2).hit;
  ASSERT_NE(ref1, ref2);  // the double reference sees one side
  const bool wt1 = closest(TriangleMethod::watertight, ray, triangles_of({tri(t1[0], t1[1], t1[2])})).id == 0;
  const bool wt2 = closest(TriangleMethod::watertight, ray, triangles_of({tri(t2[0], t2[1], t2[2])})).id == 0;
  EXPECT_EQ(wt1, ref1);
  EXPECT_EQ(wt2, ref2);
}

// ---- builder ------------------------------------------------------------------

TEST(TriangleBuild, DropsDegenerateAndNonFiniteWithCounts) {
  const Vec3<float> a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  TriangleDesc nan_normal = tri(a, b, c);
  nan_normal.normals = std::array<Vec3<float>, 3>{Vec3<float>{0, 0, 1}, Vec3<float>{kNaN, 0, 1}, Vec3<float>{0, 0, 1}};
  TriangleDesc inf_uv = tri(a, b, c);
  inf_uv.uvs = std::array<std::array<float, 2>, 3>{{{0, 0}, {kInf, 0}, {0, 1}}};
  TriangleDesc with_normals = tri({0, 0, 1}, {2, 0, 1}, {0, 2, 1});
  with_normals.normals = std::array<Vec3<float>, 3>{Vec3<float>{0, 0, 2}, Vec3<float>{0, 0, 0}, Vec3<float>{0, 3, 4}};
  BuildReport report;
  const TriangleSoA soa = triangles_of(
      {
          tri({kNaN, 0, 0}, b, c),                       // non-finite vertex
          tri(a, {kInf, 0, 0}, c),                       // non-finite vertex
          nan_normal,                                    // non-finite normal
          inf_uv,                                        // non-finite uv
          tri({-3e38f, 0, 0}, {3e38f, 0, 0}, {0, 1, 0}), // edge overflows
          tri(a, a, c),                                  // repeated vertex
          tri(a, a, a),                                  // a point
          tri({1, 2, 3}, {2, 4, 6}, {4, 8, 12}),         // collinear
          tri(a, b, {0.5f, 1e-9f, 0}),                   // height / longest edge = 1e-9
          tri(a, b, c),                                  // kept, no normals
          with_normals,                                  // kept
          tri(a, b, {0.5f, 1e-6f, 0}),                   // kept: a sliver above the tolerance
      },
      &report);
  EXPECT_EQ(report.dropped_non_finite, 5u);
  EXPECT_EQ(report.dropped_degenerate, 4u);
  EXPECT_EQ(report.kept, 3u);
  ASSERT_EQ(soa.size(), 3u);
  EXPECT_FALSE(soa.has_uvs());
  ASSERT_TRUE(soa.has_normals());
  // Missing normals: the unit geometric normal; given ones normalised, zero replaced.
  for (int k = 0; k < 3; ++k) EXPECT_FLOAT_EQ(soa.normal(0, k).z, 1.f);
  EXPECT_FLOAT_EQ(soa.normal(1, 0).z, 1.f);
  EXPECT_FLOAT_EQ(soa.normal(1, 1).z, 1.f);
  EXPECT_FLOAT_EQ(soa.normal(1, 2).y, 0.6f);
  EXPECT_FLOAT_EQ(soa.normal(1, 2).z, 0.8f);
  EXPECT_FLOAT_EQ(soa.vertex(1, 1).x, 2.f);
  // Padding: copies of the last triangle, every number finite.
  TriangleSoA copy = soa;
  for (AlignedFloats* column : copy.columns()) {
    ASSERT_TRUE(column->empty() || column->size() == padded_size(3));
    for (float x : *column) EXPECT_TRUE(std::isfinite(x));
  }
  EXPECT_EQ(soa.v2y[7], soa.v2y[2]);
}

// The sliver rule weighs twice the area against the longest of all three
// edges, whichever place it takes in the vertex order: with b = (-1, 0, 0),
// c = (1, 0, 0) and the apex a = (0, h, 0), the longest edge is b-c
// (length^2 4) and twice the area 2h, so the triangle is dropped for
// 2h <= 4 kMinTriangleRelativeHeight, in each rotation of (a, b, c), even
// at h = kMinTriangleRelativeHeight, where either edge from a alone
// (length^2 1 + h^2) would keep it. Just above the bound all three
// rotations are kept.
TEST(TriangleBuild, SliverIsJudgedByItsLongestEdgeInEveryVertexOrder) {
  const float k = float(kMinTriangleRelativeHeight);
  const float bound = 2.f * k;  // 2h = 4k, the least height kept is just above
  ASSERT_EQ(double(bound), 2.0 * kMinTriangleRelativeHeight);
  const Vec3<float> b{-1.f, 0.f, 0.f}, c{1.f, 0.f, 0.f};
  struct Case {
    float h;
    bool kept;
  };
  for (const Case& sliver : {Case{k, false}, Case{bound, false}, Case{std::nextafter(bound, 1.f), true}}) {
    const Vec3<float> a{0.f, sliver.h, 0.f};
    const std::array<std::array<Vec3<float>, 3>, 3> rotations{{{a, b, c}, {b, c, a}, {c, a, b}}};
    for (std::size_t r = 0; r < rotations.size(); ++r) {
      SCOPED_TRACE(::testing::Message() << "h = " << sliver.h << ", rotation " << r);
      BuildReport report;
      const TriangleSoA soa = triangles_of({tri(rotations[r][0], rotations[r][1], rotations[r][2])}, &report);
      EXPECT_EQ(report.dropped_degenerate, sliver.kept ? 0u : 1u);
      EXPECT_EQ(soa.size(), sliver.kept ? 1u : 0u);
    }
  }
}

TEST(TriangleBuild, OptionalColumnsEmptyWhenAbsentAndDefaultUvsWhenMixed) {
  const TriangleSoA bare = triangles_of({tri({0, 0, 0}, {1, 0, 0}, {0, 1, 0})});
  EXPECT_FALSE(bare.has_normals());
  EXPECT_FALSE(bare.has_uvs());
  EXPECT_TRUE(bare.n0x.empty() && bare.uv2v.empty());
  TriangleDesc textured = tri({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  textured.uvs = std::array<std::array<float, 2>, 3>{{{0.5f, 0.25f}, {1, 1}, {0, 0.75f}}};
  const TriangleSoA mixed = triangles_of({tri({0, 0, 0}, {1, 0, 0}, {0, 1, 0}), textured});
  ASSERT_TRUE(mixed.has_uvs());
  EXPECT_FALSE(mixed.has_normals());
  EXPECT_EQ(mixed.uv(0, 1)[0], 1.f);  // default (1, 0) at v1
  EXPECT_EQ(mixed.uv(0, 2)[1], 1.f);  // default (0, 1) at v2
  EXPECT_EQ(mixed.uv(1, 0)[1], 0.25f);
  const TriangleSoA none = triangles_of({});
  EXPECT_EQ(none.size(), 0u);
}

TEST(TriangleBuild, TrianglesFromIndexedMesh) {
  const std::vector<Vec3<float>> positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const std::vector<Face> faces = {{0, 1, 2}, {0, 2, 3}};
  const std::vector<TriangleDesc> descs = triangles_from_indexed(positions, faces);
  ASSERT_EQ(descs.size(), 2u);
  EXPECT_EQ(descs[1].p[2].y, 1.f);
  EXPECT_EQ(descs[1].p[2].x, 0.f);
  EXPECT_FALSE(descs[0].normals.has_value());
  const std::vector<Face> bad = {{0, 1, 4}};
  EXPECT_THROW(triangles_from_indexed(positions, bad), std::out_of_range);
  EXPECT_TRUE(icosphere(2).closed());
  EXPECT_TRUE(cube().closed());
}

// ---- every width equals scalar ------------------------------------------------

template <class W>
class TriangleWidths : public testing::UnitTest<W> {};
TYPED_TEST_SUITE(TriangleWidths, testing::KernelUnits);

// 9 random triangles and the 20 faces of an icosahedron (shared edges).
std::vector<TriangleDesc> mixed_triangles(RaySampler& s) {
  std::vector<TriangleDesc> descs;
  for (int i = 0; i < 9; ++i) {
    const Vec3<float> c = s.in_box({-5, -5, -5}, {5, 5, 5});
    const float size = s.uniform(0.2f, 3.f);
    descs.push_back(tri(c + s.unit_direction() * size, c + s.unit_direction() * size, c + s.unit_direction() * size));
  }
  Mesh ico = icosphere(0);
  for (Vec3<float>& p : ico.positions) p = p * 2.f + Vec3<float>{1.f, -1.f, 0.5f};
  for (const TriangleDesc& t : ico.triangles()) descs.push_back(t);
  return descs;
}

std::vector<Ray<float>> triangle_rays(RaySampler& s, const TriangleSoA& tris) {
  std::vector<Ray<float>> rays = testing::adversarial_rays(s, 40'003, {0, 0, 0}, 5.f);
  auto random_triangle = [&] {
    const std::size_t i = static_cast<std::size_t>(s.uniform_int(0, static_cast<int>(tris.size()) - 1));
    return std::array<Vec3<float>, 3>{tris.vertex(i, 0), tris.vertex(i, 1), tris.vertex(i, 2)};
  };
  for (int i = 0; i < 40'000; ++i) {  // toward points inside triangles
    const auto p = random_triangle();
    const float u = s.uniform(0.f, 1.f), v = s.uniform(0.f, 1.f - u);
    rays.push_back(s.toward(s.in_box({-9, -9, -9}, {9, 9, 9}), on_triangle(p, u, v)));
  }
  for (int i = 0; i < 10'000; ++i) {  // exactly at edges and vertices
    const auto p = random_triangle();
    const int k = s.uniform_int(0, 2);
    const Vec3<float> target = i % 3 == 0 ? p[k] : p[k] + (p[(k + 1) % 3] - p[k]) * s.uniform(0.f, 1.f);
    rays.push_back(s.toward(s.in_box({-9, -9, -9}, {9, 9, 9}), target));
  }
  for (int i = 0; i < 6'000; ++i) {  // grazing and parallel to a triangle's plane
    const auto p = random_triangle();
    const Vec3<float> n = unit(cross(p[1] - p[0], p[2] - p[0]));
    const Vec3<float> in_plane = i % 2 ? p[1] - p[0] : p[2] - p[1];
    const float tilt = i % 3 == 0 ? 0.f : s.uniform(-1e-5f, 1e-5f);
    const Vec3<float> start = on_triangle(p, s.uniform(-0.5f, 1.f), s.uniform(-0.5f, 1.f)) - in_plane * 2.f;
    rays.push_back({start + n * s.uniform(-1e-4f, 1e-4f), in_plane + n * tilt, 0.f, kInf});
  }
  for (int i = 0; i < 1'000; ++i) {  // origins at a vertex: edge functions exactly 0
    const auto p = random_triangle();
    rays.push_back({p[s.uniform_int(0, 2)], s.unit_direction(), i % 2 ? -1.f : 0.f, kInf});
  }
  for (int i = 0; i < 5'000; ++i) {  // origins on a triangle, tmin = 0
    const auto p = random_triangle();
    const float u = s.uniform(0.f, 1.f), v = s.uniform(0.f, 1.f - u);
    rays.push_back({on_triangle(p, u, v), s.unit_direction(), 0.f, kInf});
  }
  // Coherent bundles of 16 (so every width gets whole packets of them): one
  // dominant axis and sign, so the watertight test takes its fixed-axes path.
  for (int bundle = 0; bundle < 1'500; ++bundle) {
    const auto p = random_triangle();
    Vec3<float> base{s.uniform(-0.4f, 0.4f), s.uniform(-0.4f, 0.4f), s.uniform(-0.4f, 0.4f)};
    base[s.uniform_int(0, 2)] = s.uniform(0.f, 1.f) < 0.5f ? -1.f : 1.f;
    for (int i = 0; i < 16; ++i) {
      const Vec3<float> jitter{s.uniform(-0.05f, 0.05f), s.uniform(-0.05f, 0.05f), s.uniform(-0.05f, 0.05f)};
      const Vec3<float> d = base + jitter;
      const Vec3<float> target = on_triangle(p, s.uniform(-0.2f, 1.f), s.uniform(-0.2f, 1.f));
      rays.push_back({target - d * s.uniform(2.f, 9.f), d, 0.f, kInf});
    }
  }
  return rays;
}

// The rays and the scalar results, computed once for all widths.
struct WidthCase {
  TriangleSoA tris;
  RaySoA rays;
  std::map<TriangleMethod, testing::StreamResults> scalar;
};
const WidthCase& width_case() {
  static const WidthCase c = [] {
    RaySampler s(7);
    BuildReport report;
    WidthCase w;
    w.tris = build_triangles(mixed_triangles(s), report);
    w.rays = testing::to_soa(triangle_rays(s, w.tris));
    testing::poison_padding(w.rays);
    for (TriangleMethod m : kMethods)
      w.scalar[m] = testing::run_streams(study_triangle_streams<KernelUnit::scalar>(m), w.rays, w.tris);
    return w;
  }();
  return c;
}

TYPED_TEST(TriangleWidths, MatchesScalarBitForBit) {
  const WidthCase& c = width_case();
  ASSERT_EQ(c.tris.size(), 29u);  // not a multiple of any width
  EXPECT_GE(c.rays.count, 100'000u);
  for (TriangleMethod m : kMethods) {
    SCOPED_TRACE(method_name(m));
    const testing::StreamResults& ref = c.scalar.at(m);
    // The scalar unit is the reference itself: only its scan-vs-packets check is new.
    const testing::StreamResults got =
        TestFixture::kUnit == KernelUnit::scalar
            ? ref
            : testing::run_streams(study_triangle_streams<TestFixture::kUnit>(m), c.rays, c.tris);
    testing::expect_results_match_scalar(ref, got);
    EXPECT_GT(ref.closest_packets.hit_count(), c.rays.count * 2 / 5);  // the test exercises hits
  }
}

// The frame fixed once per ray (with_fixed_axes, the single-ray BVH walk)
// gives the test's own result bit for bit, in each of the six frames.
TEST(TriangleKernel, WatertightFrameFixedPerRayGivesTheSameBits) {
  const WidthCase& c = width_case();
  std::set<int> frames;
  std::size_t hits = 0;
  for (std::size_t r = 0; r < c.rays.count; ++r) {
    const Ray<float> ray = c.rays.get(r);
    const WatertightRay<float> own = TriangleWatertight::prepare(ray);
    frames.insert(own.shared_axes);
    TriangleWatertight::with_fixed_axes<float>(ray, [&]<class Axes>(const WatertightRay<float>& fixed, Axes) {
      for (std::size_t i = 0; i < c.tris.size(); ++i) {
        const TriangleLanes<float> t = c.tris.broadcast<float>(i);
        Candidate<float> want, got;
        const bool want_hit = TriangleWatertight::intersect(own, t, ray.tmax, true, want);
        const bool got_hit = TriangleWatertight::intersect_in<Axes>(fixed, t, ray.tmax, true, got);
        ASSERT_EQ(got_hit, want_hit) << "ray " << r << ", triangle " << i;
        if (!want_hit) continue;
        ++hits;
        const std::array<float, 6> a{want.t, want.u, want.v, want.ng.x, want.ng.y, want.ng.z};
        const std::array<float, 6> b{got.t, got.u, got.v, got.ng.x, got.ng.y, got.ng.z};
        for (std::size_t k = 0; k < a.size(); ++k) {
          ASSERT_EQ(std::bit_cast<std::uint32_t>(a[k]), std::bit_cast<std::uint32_t>(b[k]))
              << "ray " << r << ", triangle " << i << ", value " << k;
        }
      }
    });
  }
  EXPECT_EQ(frames, (std::set<int>{0, 1, 2, 3, 4, 5}));
  EXPECT_GT(hits, c.rays.count / 2);
}

// ---- stability ------------------------------------------------------------------

struct LeakCount {
  std::size_t rays = 0, edge_leaks = 0, vertex_leaks = 0;
};

// Rays from inside `mesh` (origins within `inner` of `center`) aimed exactly
// at points of its edges (per_edge each, at a float parameter along the edge)
// and at its vertices (per_vertex each); a ray that hits nothing leaked.
// Any-hit over a triangle store: the scan, or a BVH walk (see below).
using OcclusionQuery = std::function<void(const RaySoA&, const TriangleSoA&, OcclusionSoA&)>;

LeakCount count_leaks(const OcclusionQuery& query, const Mesh& mesh, const Vec3<float>& center, float inner,
                      int per_edge, int per_vertex, std::uint32_t seed) {
  RaySampler s(seed);
  const TriangleSoA soa = triangles_of(mesh.triangles());
  EXPECT_EQ(soa.size(), mesh.faces.size());
  std::vector<Ray<float>> rays;
  std::vector<bool> at_vertex;
  auto origin = [&] { return center + s.unit_direction() * s.uniform(0.f, inner); };
  for (const auto& [a, b] : mesh.edges()) {
    const Vec3<float> pa = mesh.positions[a], pb = mesh.positions[b];
    for (int i = 0; i < per_edge; ++i) {
      rays.push_back(s.toward(origin(), pa + (pb - pa) * s.uniform(0.f, 1.f)));
      at_vertex.push_back(false);
    }
  }
  for (const Vec3<float>& p : mesh.positions) {
    for (int i = 0; i < per_vertex; ++i) {
      rays.push_back(s.toward(origin(), p));
      at_vertex.push_back(true);
    }
  }
  const RaySoA soa_rays = testing::to_soa(rays);
  OcclusionSoA occlusion(soa_rays);
  query(soa_rays, soa, occlusion);
  LeakCount count;
  count.rays = rays.size();
  for (std::size_t i = 0; i < rays.size(); ++i) {
    if (occlusion.occluded[i] == 0) ++(at_vertex[i] ? count.vertex_leaks : count.edge_leaks);
  }
  return count;
}

TEST(TriangleStability, WatertightNeverLeaksThroughSharedEdgesAndVertices) {
  RaySampler s(2024);
  const Vec3<float> jitter_center{3.1f, -1.7f, 0.9f};
  struct Case {
    const char* name;
    Mesh mesh;
    Vec3<float> center;
    float inner;
    int per_edge, per_vertex;
  };
  const Case cases[] = {
      {"icosphere(2)", icosphere(2), {0, 0, 0}, 0.5f, 800, 400},
      {"cube", cube(), {0, 0, 0}, 0.5f, 8000, 4000},
      {"jittered", jittered_polyhedron(s, jitter_center), jitter_center, 0.5f, 800, 400},
  };
  std::size_t total_rays = 0, watertight_leaks = 0, mt_leaks = 0;
  for (const Case& c : cases) {
    ASSERT_TRUE(c.mesh.closed()) << c.name;
    for (TriangleMethod m : kMethods) {
      const LeakCount n = count_leaks(fastest_streams(m).occluded_packets, c.mesh, c.center, c.inner, c.per_edge,
                                      c.per_vertex, 99);
      std::printf("[ measured ] %-12s %-15s %zu triangles, %zu rays: %zu leaked at edges, %zu at vertices\n",
                  c.name, method_name(m), c.mesh.faces.size(), n.rays, n.edge_leaks, n.vertex_leaks);
      const std::size_t leaks = n.edge_leaks + n.vertex_leaks;
      if (m == TriangleMethod::watertight) {
        total_rays += n.rays;
        watertight_leaks += leaks;
        EXPECT_EQ(leaks, 0u) << c.name;
      } else {
        mt_leaks += leaks;
      }
    }
  }
  EXPECT_GE(total_rays, 1'000'000u);
  EXPECT_EQ(watertight_leaks, 0u);
  // The seed method's failure point: epsilon-free Moller-Trumbore leaks.
  EXPECT_GT(mt_leaks, 0u);
}

TEST(TriangleStability, WatertightNeverLeaksThroughTheBvh) {
  // The same rays through a BVH over the mesh (conservative slab tests),
  // every node width, packets and single rays, on the widest unit here.
  const BvhStreams<TriangleSoA> tree = with_kernel_unit(kernel_unit_for(best_supported_isa()), [](auto u) {
    return study_triangle_bvh_streams<decltype(u)::value>(TriangleMethod::watertight);
  });
  const Mesh mesh = icosphere(3);
  const std::vector<TriangleDesc> descs = mesh.triangles();
  std::size_t rays = 0;
  for (int width : {2, 4, 8}) {
    for (BvhTraversal traversal : {BvhTraversal::packets, BvhTraversal::single}) {
      const OcclusionQuery through_bvh = [&](const RaySoA& r, const TriangleSoA& soa, OcclusionSoA& occlusion) {
        TriangleSoA store = soa;
        BvhBuildOptions options;
        options.width = width;
        options.max_leaf_size = 2;  // a deep tree: many boxes share each edge
        const Bvh bvh = reorder_for_bvh(DescRefs<TriangleDesc>(descs), build_triangles, options, store);
        tree.any_hits(r, store, bvh, occlusion, traversal);
      };
      const LeakCount n = count_leaks(through_bvh, mesh, {0, 0, 0}, 0.5f, 150, 150, 7);
      rays += n.rays;
      EXPECT_EQ(n.edge_leaks + n.vertex_leaks, 0u) << "width " << width << ", traversal " << int(traversal);
    }
  }
  EXPECT_GE(rays, 1'000'000u);
}

// Whether float rounding may decide method m's hit or miss for this ray and
// triangle: some exact quantity whose sign the method takes lies within its
// first-order rounding bound. Exact values come from double arithmetic on
// the float inputs (whose own rounding is 2^-29 of these bounds). With
// eps = 2^-24, R the largest |component| of v_i - o and D of d:
bool rounding_may_decide(TriangleMethod m, const Ray<float>& ray, const std::array<Vec3<float>, 3>& p) {
  const double eps = std::ldexp(1.0, -24);
  const Vec3<double> o = to_double(ray.origin), d = to_double(ray.direction);
  std::array<Vec3<double>, 3> rel;
  double R = 0.0;
  for (int k = 0; k < 3; ++k) {
    rel[k] = to_double(p[k]) - o;
    R = std::max({R, std::fabs(rel[k].x), std::fabs(rel[k].y), std::fabs(rel[k].z)});
  }
  if (m == TriangleMethod::watertight) {
    // Woop, Benthin, Wald 2013: a sheared coordinate (v-o)[kx] - S (v-o)[kz]
    // (|S| = |d[kx] / d[kz]| <= 1, up to 2R) carries three roundings (v - o,
    // S, the fma), so errs by <= 6 eps R; an edge function U = Cx By - Cy Bx
    // then errs by <= 2 (2R 6 eps R + 2R 6 eps R) + 2 (4 eps R^2) (the
    // products) + 8 eps R^2 (the difference) = 64 eps R^2, at first order.
    const auto ax = [&](const Vec3<double>& v, int a) { return a == 0 ? v.x : a == 1 ? v.y : v.z; };
    const double adx = std::fabs(d.x), ady = std::fabs(d.y), adz = std::fabs(d.z);
    const int kz = adz >= adx && adz >= ady ? 2 : ady >= adx ? 1 : 0, kx = (kz + 1) % 3, ky = (kz + 2) % 3;
    const double dz = ax(d, kz), sx = ax(d, kx) / dz, sy = ax(d, ky) / dz;
    std::array<Vec3<double>, 3> s;
    for (int k = 0; k < 3; ++k) {
      s[k] = {ax(rel[k], kx) - sx * ax(rel[k], kz), ax(rel[k], ky) - sy * ax(rel[k], kz), ax(rel[k], kz) / dz};
    }
    const double U = s[2].x * s[1].y - s[2].y * s[1].x, V = s[0].x * s[2].y - s[0].y * s[2].x,
                 W = s[1].x * s[0].y - s[1].y * s[0].x;
    const double edge = 64.0 * eps * R * R;
    if (std::min({std::fabs(U), std::fabs(V), std::fabs(W)}) <= edge) return true;
    // t's numerator U Az + V Bz + W Cz (|z| <= R / |d[kz]|, three roundings
    // each): errs by <= 3 edge R / |d[kz]| + 6 eps sum |U Az|.
    const double products = std::fabs(U * s[0].z) + std::fabs(V * s[1].z) + std::fabs(W * s[2].z);
    return std::fabs(U * s[0].z + V * s[1].z + W * s[2].z) <= 3.0 * edge * R / std::fabs(dz) + 6.0 * eps * products;
  }
  // Moller-Trumbore, components: e = v - v0 (<= 2R, error 2 eps R),
  // T = o - v0 (<= R, eps R); p = d x e2 (<= 4DR) errs by <= 12 eps DR,
  // q = T x e1 (<= 4R^2) by <= 16 eps R^2; then det = e1.p <= 160 eps DR^2,
  // u's numerator T.p and v's d.q <= 80 eps DR^2, t's e2.q <= 184 eps R^3
  // (propagated, three products, two sums). u + v <= 1 is the sign of
  // det - Nu - Nv, off by <= dNu + dNv + (|u| + |v|) ddet + 3 eps (|Nu| + |Nv|);
  // doubled where divided by det, which is then at least twice its error.
  const double D = std::max({std::fabs(d.x), std::fabs(d.y), std::fabs(d.z)});
  const Vec3<double> e1 = rel[1] - rel[0], e2 = rel[2] - rel[0], t_offset = o - to_double(p[0]);
  const Vec3<double> pv = cross(d, e2), q = cross(t_offset, e1);
  const double det = dot(e1, pv), nu = dot(t_offset, pv), nv = dot(d, q), nt = dot(e2, q);
  const double det_error = 160.0 * eps * D * R * R, uv_error = 80.0 * eps * D * R * R;
  if (std::fabs(det) <= 2.0 * det_error) return true;
  if (std::fabs(nu) <= uv_error || std::fabs(nv) <= uv_error || std::fabs(nt) <= 184.0 * eps * R * R * R) return true;
  const double u = nu / det, v = nv / det;
  const double w_error = 2.0 * (2.0 * uv_error + (std::fabs(u) + std::fabs(v)) * det_error) +
                         6.0 * eps * (std::fabs(nu) + std::fabs(nv));
  return std::fabs(det - nu - nv) <= w_error;
}

TEST(TriangleStability, GrazingAndParallelRaysNeverGiveNaN) {
  RaySampler s(31);
  std::vector<TriangleDesc> descs;
  for (int i = 0; i < 29; ++i) {
    const Vec3<float> c = s.in_box({-50, -50, -50}, {50, 50, 50});
    const float size = s.uniform(0.01f, 10.f);
    descs.push_back(tri(c + s.unit_direction() * size, c + s.unit_direction() * size, c + s.unit_direction() * size));
  }
  const TriangleSoA tris = triangles_of(descs);
  ASSERT_EQ(tris.size(), 29u);
  std::vector<Ray<float>> rays;
  std::vector<std::size_t> target;
  for (std::size_t i = 0; i < tris.size(); ++i) {
    const std::array<Vec3<float>, 3> p{tris.vertex(i, 0), tris.vertex(i, 1), tris.vertex(i, 2)};
    const Vec3<float> n = unit(cross(p[1] - p[0], p[2] - p[0]));
    for (int j = 0; j < 4'000; ++j) {
      const Vec3<float> in_plane = p[(j + 1) % 3] - p[j % 3] + (p[(j + 2) % 3] - p[j % 3]) * s.uniform(-1.f, 1.f);
      const float tilt = j % 4 == 0 ? 0.f : std::ldexp(s.uniform(-1.f, 1.f), -s.uniform_int(2, 40));
      const float offset = j % 8 < 2 ? 0.f : std::ldexp(s.uniform(-1.f, 1.f), -s.uniform_int(0, 30));
      const Vec3<float> start = on_triangle(p, s.uniform(-0.2f, 1.f), s.uniform(-0.2f, 1.f)) - in_plane * 3.f;
      rays.push_back({start + n * offset, in_plane + n * (tilt * length(in_plane)), 0.f, kInf});
      target.push_back(i);
    }
  }
  const RaySoA soa = testing::to_soa(rays);
  for (TriangleMethod m : kMethods) {
    SCOPED_TRACE(method_name(m));
    const testing::StreamResults r = testing::run_streams(fastest_streams(m), soa, tris);
    std::size_t hits = 0, outside_band = 0;
    for (const HitSoA* hs : {&r.closest_packets, &r.closest_scan}) {
      for (std::size_t i = 0; i < hs->count; ++i) {
        const Hit<float> h = hs->get(i);
        if (h.id == kNoHit) continue;
        ASSERT_TRUE(std::isfinite(h.t) && std::isfinite(h.u) && std::isfinite(h.v)) << "ray " << i;
        ASSERT_TRUE(std::isfinite(h.ng.x) && std::isfinite(h.ng.y) && std::isfinite(h.ng.z)) << "ray " << i;
        ASSERT_GT(h.t, 0.f);
      }
    }
    for (std::size_t i = 0; i < rays.size(); ++i) {
      const std::size_t k = target[i];
      const Reference ref = reference(rays[i], {tris.vertex(k, 0), tris.vertex(k, 1), tris.vertex(k, 2)});
      // Only the aimed-at triangle: another one may be hit first.
      const Hit<float> h = r.closest_packets.get(i);
      const bool hit_target = h.id == static_cast<std::int32_t>(k);
      hits += hit_target;
      if ((hit_target || h.id == kNoHit) && hit_target != ref.hit) {
        const bool explained = rounding_may_decide(m, rays[i], {tris.vertex(k, 0), tris.vertex(k, 1), tris.vertex(k, 2)});
        outside_band += !explained;
        EXPECT_TRUE(explained) << "ray " << i << " (triangle " << k << ") disagrees with double beyond the rounding bound";
      }
    }
    EXPECT_EQ(outside_band, 0u) << "hit/miss decisions wrong beyond the method's rounding error";
    EXPECT_GT(hits, 0u) << "the rays exercise hits";
  }
}

TEST(TriangleStability, ExactlyParallelRaysOffThePlaneMiss) {
  // Lattice triangles: the edges, the in-plane directions and the offsets
  // along the (integer) normal are exact, so these rays are parallel to their
  // own triangle and off its plane; each triangle is tested alone.
  RaySampler s(5);
  auto lattice = [&](int range) { return float(s.uniform_int(-range, range)); };
  std::size_t tested = 0, rays_total = 0;
  for (int i = 0; i < 37; ++i) {
    const Vec3<float> v0{lattice(64) * 0.25f, lattice(64) * 0.25f, lattice(64) * 0.25f};
    const Vec3<float> e1{lattice(9), lattice(9), lattice(9)}, e2{lattice(9), lattice(9), lattice(9)};
    const Vec3<float> n = cross(e1, e2);
    const TriangleSoA one = triangles_of({tri(v0, v0 + e1, v0 + e2)});
    if (one.size() != 1) continue;
    ++tested;
    std::vector<Ray<float>> rays;
    for (int j = 0; j < 500; ++j) {
      const Vec3<float> d = e1 * lattice(4) + e2 * lattice(4);
      const Vec3<float> in_plane = v0 + e1 * (lattice(8) * 0.125f) + e2 * (lattice(8) * 0.125f);
      const float k = float(s.uniform_int(1, 64)) * (j % 2 ? 0.0625f : -0.0625f);
      rays.push_back({in_plane + n * k - d * 4.f, d, -kInf, kInf});
    }
    rays_total += rays.size();
    const RaySoA soa = testing::to_soa(rays);
    for (TriangleMethod m : kMethods) {
      SCOPED_TRACE(method_name(m));
      const testing::StreamResults r = testing::run_streams(fastest_streams(m), soa, one);
      EXPECT_EQ(r.closest_packets.hit_count(), 0u) << "triangle " << i;
      EXPECT_EQ(r.closest_scan.hit_count(), 0u) << "triangle " << i;
    }
  }
  EXPECT_GT(tested, 30u);
  EXPECT_GT(rays_total, 15'000u);
}

TEST(TriangleStability, DegenerateTrianglesNeverHitEvenPastTheBuilder) {
  RaySampler s(13);
  std::vector<TriangleDesc> degenerate;
  auto lattice = [&](int range) { return float(s.uniform_int(-range, range)); };
  for (int i = 0; i < 12; ++i) {
    const Vec3<float> v0{lattice(32) * 0.25f, lattice(32) * 0.25f, lattice(32) * 0.25f};
    Vec3<float> e{lattice(3), lattice(3), lattice(3)};
    if (e.x == 0 && e.y == 0 && e.z == 0) e = {1, -2, 3};
    degenerate.push_back(tri(v0, v0 + e * lattice(4), v0 + e * lattice(4)));  // collinear or repeated
    degenerate.push_back(tri(v0, v0, v0 + e * 0.5f));                        // repeated vertex
    degenerate.push_back(tri(v0, v0, v0));                                   // a point
  }
  degenerate.push_back(tri({0, 0, 0}, {1, 0, 0}, {2, 0, 0}));
  degenerate.push_back(tri({0.1f, 0.2f, 0.3f}, {0.2f, 0.4f, 0.6f}, {0.1f, 0.2f, 0.3f}));
  const std::size_t zero_area = degenerate.size();
  degenerate.push_back(tri({kNaN, 0, 0}, {1, 0, 0}, {0, 1, 0}));
  degenerate.push_back(tri({0, 0, 0}, {1, kNaN, 0}, {0, 1, 0}));
  degenerate.push_back(tri({kNaN, kNaN, kNaN}, {kNaN, kNaN, kNaN}, {kNaN, kNaN, kNaN}));
  BuildReport report;
  EXPECT_EQ(triangles_of(degenerate, &report).size(), 0u);
  EXPECT_EQ(report.dropped_degenerate, zero_area);
  EXPECT_EQ(report.dropped_non_finite, degenerate.size() - zero_area);

  // Straight into the SoA, bypassing the builder.
  TriangleSoA raw;
  raw.count = degenerate.size();
  AlignedFloats* columns[3][3] = {{&raw.v0x, &raw.v0y, &raw.v0z}, {&raw.v1x, &raw.v1y, &raw.v1z},
                                  {&raw.v2x, &raw.v2y, &raw.v2z}};
  for (int k = 0; k < 3; ++k) {
    for (int axis = 0; axis < 3; ++axis) {
      columns[k][axis]->resize(padded_size(raw.count));
      for (std::size_t i = 0; i < raw.count; ++i) (*columns[k][axis])[i] = degenerate[i].p[k][axis];
      pad_column(*columns[k][axis], raw.count);
    }
  }
  std::vector<Ray<float>> rays = testing::adversarial_rays(s, 10'003, {0, 0, 0}, 8.f);
  for (int i = 0; i < 20'000; ++i) {  // at points of the segments and vertices
    const TriangleDesc& d = degenerate[static_cast<std::size_t>(s.uniform_int(0, static_cast<int>(zero_area) - 1))];
    const int k = s.uniform_int(0, 2);
    const Vec3<float> target = d.p[k] + (d.p[(k + 1) % 3] - d.p[k]) * (i % 2 ? s.uniform(0.f, 1.f) : 0.f);
    rays.push_back(s.toward(s.in_box({-20, -20, -20}, {20, 20, 20}), target));
  }
  RaySoA soa = testing::to_soa(rays);
  testing::poison_padding(soa);
  for (TriangleMethod m : kMethods) {
    SCOPED_TRACE(method_name(m));
    const testing::StreamResults r = testing::expect_streams_match_scalar(study_triangle_streams<KernelUnit::scalar>(m),
                                                                          fastest_streams(m), soa, raw);
    EXPECT_EQ(r.closest_packets.hit_count(), 0u);
    EXPECT_EQ(r.closest_scan.hit_count(), 0u);
    for (std::size_t i = 0; i < rays.size(); ++i) {
      ASSERT_EQ(r.occluded_packets.occluded[i], 0) << "ray " << i;
      ASSERT_TRUE(std::isnan(r.closest_packets.t[i]) == std::isnan(rays[i].tmax)) << "ray " << i;
    }
  }
}

TEST(TriangleStability, SelfIntersectionFromOriginsOnTheSurface) {
  // Origins at float points of a triangle (barycentric, rounded), random unit
  // directions, tmin = 0: the rounded origin lies a few ulps off the plane, so
  // about half of the rays (those heading back through the plane) hit their
  // own triangle at a tiny t. With tmin = 1e-4 |coords| a self hit needs
  // |cos(d, n)| <= distance / tmin, i.e. a grazing ray.
  RaySampler s(17);
  constexpr int kTriangles = 64, kRaysEach = 2'000;
  for (TriangleMethod m : kMethods) {
    SCOPED_TRACE(method_name(m));
    std::size_t self_hits = 0, self_hits_offset = 0, rays_total = 0;
    double worst_t = 0;         // largest t |d| / |coords| among self hits, tmin = 0
    double worst_cosine = 0;    // largest |cos(d, n)| among self hits, tmin = 1e-4 |coords|
    RaySampler tri_sampler(17);
    for (int i = 0; i < kTriangles; ++i) {
      const Vec3<float> c = tri_sampler.in_box({-100, -100, -100}, {100, 100, 100});
      const float size = tri_sampler.uniform(0.1f, 10.f);
      const std::array<Vec3<float>, 3> p{c + tri_sampler.unit_direction() * size,
                                         c + tri_sampler.unit_direction() * size,
                                         c + tri_sampler.unit_direction() * size};
      const TriangleSoA one = triangles_of({tri(p[0], p[1], p[2])});
      if (one.size() != 1) continue;
      const Vec3<double> n = cross(to_double(p[1]) - to_double(p[0]), to_double(p[2]) - to_double(p[0]));
      const double n_length = std::sqrt(dot(n, n));
      const float magnitude = std::max({std::abs(c.x), std::abs(c.y), std::abs(c.z)}) + size;
      std::vector<Ray<float>> rays;
      for (int j = 0; j < kRaysEach; ++j) {
        const float u = s.uniform(0.f, 1.f), v = s.uniform(0.f, 1.f - u);
        rays.push_back({on_triangle(p, u, v), s.unit_direction(), 0.f, kInf});
      }
      const RaySoA soa = testing::to_soa(rays);
      HitSoA hits(soa);
      fastest_streams(m).closest_packets(soa, one, hits);
      for (std::size_t j = 0; j < rays.size(); ++j) {
        if (hits.id[j] == kNoHit) continue;
        ++self_hits;
        worst_t = std::max(worst_t, double(hits.t[j]) / magnitude);  // |d| = 1
      }
      for (Ray<float>& r : rays) r.tmin = 1e-4f * magnitude;
      const RaySoA offset_soa = testing::to_soa(rays);
      HitSoA offset_hits(offset_soa);
      fastest_streams(m).closest_packets(offset_soa, one, offset_hits);
      for (std::size_t j = 0; j < rays.size(); ++j) {
        if (offset_hits.id[j] == kNoHit) continue;
        ++self_hits_offset;
        worst_cosine = std::max(worst_cosine, std::abs(dot(to_double(rays[j].direction), n)) / n_length);
      }
      rays_total += rays.size();
    }
    std::printf("[ measured ] self-intersection %-15s %zu rays, tmin=0: %zu self hits (%.2f%%), largest "
                "t/|coords| %.3g; tmin=1e-4|coords|: %zu self hits, largest |cos| %.3g\n",
                method_name(m), rays_total, self_hits, 100.0 * double(self_hits) / double(rays_total), worst_t,
                self_hits_offset, worst_cosine);
    EXPECT_GT(rays_total, 100'000u);
    EXPECT_LT(double(self_hits), 0.6 * double(rays_total));  // at most the half heading through the plane
    EXPECT_LT(self_hits_offset * 1000, self_hits);            // the offset removes > 99.9%
    EXPECT_LT(worst_cosine, 1e-2);                            // and what remains grazes
  }
}

TEST(TriangleStability, FarFromOriginDistanceMatchesDoubleReference) {
  // Triangles of size 1..10 at distance D from the world origin; rays from
  // the world origin (t ~ 1, |d| ~ D) or from 20 units away, toward interior
  // points. Against Moller-Trumbore in double on the same float inputs:
  //   t error in ulps, and times |cos(d, n)| (the grazing amplification
  //   removed); misses of rays the reference hits, and how far from the
  //   nearest edge (in ulp(D), in the plane) the farthest such miss lands.
  RaySampler s(23);
  for (float distance : {1e5f, 3e5f, 1e6f}) {
    const double ulp_d = double(std::nextafter(distance, kInf) - distance);
    for (bool from_zero : {true, false}) {
      for (TriangleMethod m : kMethods) {
        double worst_ulps = 0, sum_ulps = 0, worst_scaled = 0, worst_miss_margin = 0;
        std::size_t misses = 0, n = 0;
        RaySampler tri_sampler(41);
        for (int i = 0; i < 100; ++i) {
          const Vec3<float> c = tri_sampler.unit_direction() * distance;
          const float size = tri_sampler.uniform(1.f, 10.f);
          const std::array<Vec3<float>, 3> p{c + tri_sampler.unit_direction() * size,
                                             c + tri_sampler.unit_direction() * size,
                                             c + tri_sampler.unit_direction() * size};
          const TriangleSoA one = triangles_of({tri(p[0], p[1], p[2])});
          if (one.size() != 1) continue;
          const Vec3<double> q0 = to_double(p[0]), q1 = to_double(p[1]), q2 = to_double(p[2]);
          const Vec3<double> normal = cross(q1 - q0, q2 - q0);
          const double twice_area = std::sqrt(dot(normal, normal));
          // Heights over the edges opposite v0, v1, v2.
          const double height[3] = {twice_area / std::sqrt(dot(q2 - q1, q2 - q1)),
                                    twice_area / std::sqrt(dot(q2 - q0, q2 - q0)),
                                    twice_area / std::sqrt(dot(q1 - q0, q1 - q0))};
          std::vector<Ray<float>> rays;
          for (int j = 0; j < 500; ++j) {
            const float u = s.uniform(0.1f, 0.8f), v = s.uniform(0.1f, 0.9f - u);
            const Vec3<float> o = from_zero ? Vec3<float>{0, 0, 0} : c + s.unit_direction() * 20.f;
            rays.push_back(s.toward(o, on_triangle(p, u, v)));
          }
          const RaySoA soa = testing::to_soa(rays);
          HitSoA hits(soa);
          fastest_streams(m).closest_packets(soa, one, hits);
          for (std::size_t j = 0; j < rays.size(); ++j) {
            const Reference ref = reference(rays[j], p);
            if (!ref.hit) continue;  // the rounded target fell outside
            ++n;
            if (hits.id[j] == kNoHit) {
              ++misses;
              const double edge_distance = std::min({(1 - ref.u - ref.v) * height[0], ref.u * height[1], ref.v * height[2]});
              worst_miss_margin = std::max(worst_miss_margin, edge_distance / ulp_d);
              continue;
            }
            const Vec3<double> d = to_double(rays[j].direction);
            const double cosine = std::abs(dot(d, normal)) / (std::sqrt(dot(d, d)) * twice_area);
            const float tf = static_cast<float>(ref.t);
            const double ulp = double(std::nextafter(tf, kInf) - tf);
            const double ulps = std::abs(double(hits.t[j]) - ref.t) / ulp;
            worst_ulps = std::max(worst_ulps, ulps);
            worst_scaled = std::max(worst_scaled, ulps * cosine);
            sum_ulps += ulps;
          }
        }
        std::printf("[ measured ] far %.0e %-9s %-15s %zu rays: t error mean %.2f ulp, max %.1f ulp, "
                    "max x|cos| %.1f; %zu misses, farthest %.1f ulp(D) inside\n",
                    double(distance), from_zero ? "from-zero" : "near", method_name(m), n, sum_ulps / double(n),
                    worst_ulps, worst_scaled, misses, worst_miss_margin);
        EXPECT_GT(n, 40'000u);
        EXPECT_LT(worst_scaled, 32.0);
        // Misses stay within a few tens of ulp(D) of an edge; Moller-Trumbore's
        // T.p and d.q cancel at |T| ~ D and it misses farther inside.
        EXPECT_LT(worst_miss_margin, m == TriangleMethod::watertight ? 64.0 : 256.0);
      }
    }
  }
}

}  // namespace
}  // namespace quiver
