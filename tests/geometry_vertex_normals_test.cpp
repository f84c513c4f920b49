// Angle-weighted vertex normals with a crease angle (geometry/vertex_normals.h):
// hard cube edges stay hard below 90 degrees and average above; a fine
// sphere's normals are radial; a flat grid's are the plane's; the weight is
// the corner angle (a face split in two weighs as before), not the face
// count or area; degenerate faces, high-valence vertices and bad arguments.
#include <gtest/gtest.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <span>
#include <stdexcept>
#include <vector>

#include "geometry/vertex_normals.h"

namespace quiver {
namespace {

using Normals = std::vector<std::optional<CornerNormals>>;

// Each triangle's smoothed normals, or nullopt where it stays faceted.
Normals normals_of(std::span<const Vec3<float>> positions, std::span<const TriangleIndices> triangles,
                   double crease_angle_degrees) {
  Normals result(triangles.size());
  smooth_vertex_normals(positions, triangles, crease_angle_degrees,
                        [&](std::size_t t, const CornerNormals& normals) { result[t] = normals; });
  return result;
}

Vec3<double> unit(double x, double y, double z) {
  const double l = std::sqrt(x * x + y * y + z * z);
  return {x / l, y / l, z / l};
}

// The angle in degrees between a float normal and a unit double vector.
double degrees_between(const Vec3<float>& n, const Vec3<double>& expected) {
  const Vec3<double> a = unit(n.x, n.y, n.z);
  const double c = a.x * expected.x + a.y * expected.y + a.z * expected.z;
  return std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

Vec3<double> face_normal(const std::vector<Vec3<float>>& p, const TriangleIndices& t) {
  const Vec3<double> a{p[t[0]].x, p[t[0]].y, p[t[0]].z};
  const Vec3<double> b{p[t[1]].x, p[t[1]].y, p[t[1]].z};
  const Vec3<double> c{p[t[2]].x, p[t[2]].y, p[t[2]].z};
  const Vec3<double> n = cross(b - a, c - a);
  return unit(n.x, n.y, n.z);
}

// The unit cube, vertex i at (i & 1, i >> 1 & 1, i >> 2 & 1), its six faces
// wound outwards, each split into two triangles.
struct Mesh {
  std::vector<Vec3<float>> positions;
  std::vector<TriangleIndices> triangles;
};

Mesh cube() {
  Mesh m;
  for (std::uint32_t i = 0; i < 8; ++i) m.positions.push_back({float(i & 1), float(i >> 1 & 1), float(i >> 2 & 1)});
  const std::uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.triangles.push_back({q[0], q[1], q[2]});
    m.triangles.push_back({q[0], q[2], q[3]});
  }
  return m;
}

TEST(VertexNormals, CubeEdgesStayHardBelowNinetyDegreesAndAverageAbove) {
  const Mesh m = cube();
  // 60 degrees: each corner sees only its own face's two triangles, so
  // every triangle keeps its face normal (no normals at all).
  const Normals hard = normals_of(m.positions, m.triangles, 60.0);
  ASSERT_EQ(hard.size(), 12u);
  for (const auto& n : hard) EXPECT_FALSE(n.has_value());
  // 100 degrees: the three faces at a corner (at 90 degrees) average, each
  // with a corner angle of 90 degrees in all (one triangle of 90, or two of
  // 45), so every corner normal is the diagonal through that corner.
  const Normals soft = normals_of(m.positions, m.triangles, 100.0);
  for (std::size_t t = 0; t < 12; ++t) {
    ASSERT_TRUE(soft[t].has_value()) << t;
    for (std::size_t k = 0; k < 3; ++k) {
      const Vec3<float>& p = m.positions[m.triangles[t][k]];
      const Vec3<double> diagonal = unit(2.0 * p.x - 1.0, 2.0 * p.y - 1.0, 2.0 * p.z - 1.0);
      EXPECT_LT(degrees_between((*soft[t])[k], diagonal), 1e-5) << t << " " << k;
    }
  }
}

// A UV sphere of 96 segments and 48 rings, one vertex at each pole (9,024 triangles).
Mesh uv_sphere() {
  constexpr std::uint32_t kSegments = 96, kRings = 48;
  Mesh m;
  m.positions.push_back({0.f, 1.f, 0.f});
  for (std::uint32_t r = 1; r < kRings; ++r) {
    const double theta = std::numbers::pi * r / kRings;
    for (std::uint32_t s = 0; s < kSegments; ++s) {
      const double phi = 2.0 * std::numbers::pi * s / kSegments;
      m.positions.push_back({float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)),
                             float(std::sin(theta) * std::sin(phi))});
    }
  }
  m.positions.push_back({0.f, -1.f, 0.f});
  const auto ring = [&](std::uint32_t r, std::uint32_t s) { return 1 + (r - 1) * kSegments + s % kSegments; };
  const std::uint32_t south = std::uint32_t(m.positions.size() - 1);
  for (std::uint32_t s = 0; s < kSegments; ++s) {
    m.triangles.push_back({0, ring(1, s + 1), ring(1, s)});
    for (std::uint32_t r = 1; r + 1 < kRings; ++r) {
      m.triangles.push_back({ring(r, s), ring(r, s + 1), ring(r + 1, s + 1)});
      m.triangles.push_back({ring(r, s), ring(r + 1, s + 1), ring(r + 1, s)});
    }
    m.triangles.push_back({south, ring(kRings - 1, s), ring(kRings - 1, s + 1)});
  }
  return m;
}

TEST(VertexNormals, AFineSpheresNormalsAreRadial) {
  const Mesh m = uv_sphere();
  const Normals normals = normals_of(m.positions, m.triangles, kDefaultCreaseAngleDegrees);
  double worst = 0.0, worst_faceted = 0.0;
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    ASSERT_TRUE(normals[t].has_value()) << t;
    for (std::size_t k = 0; k < 3; ++k) {
      const Vec3<float>& p = m.positions[m.triangles[t][k]];
      const Vec3<double> radial = unit(p.x, p.y, p.z);
      worst = std::max(worst, degrees_between((*normals[t])[k], radial));
      const Vec3<double> f = face_normal(m.positions, m.triangles[t]);
      worst_faceted = std::max(worst_faceted, degrees_between(Vec3<float>{float(f.x), float(f.y), float(f.z)}, radial));
    }
  }
  EXPECT_LT(worst, 0.05);          // degrees
  EXPECT_GT(worst_faceted, 1.0);   // the face normals are not: the check can fail
}

// The faces are shared among threads in blocks; each corner's sum runs in
// corner order, so any thread count gives the same bits.
TEST(VertexNormals, TheSameBitsForAnyThreadCount) {
  const Mesh m = uv_sphere();
  const auto normals_with = [&](int threads) {
    oneapi::tbb::task_arena arena(threads);
    return arena.execute([&] { return normals_of(m.positions, m.triangles, kDefaultCreaseAngleDegrees); });
  };
  const Normals one = normals_with(1);
  for (int threads : {2, 3, 8}) {
    const Normals many = normals_with(threads);
    ASSERT_EQ(many.size(), one.size());
    std::size_t differing = 0;
    for (std::size_t t = 0; t < one.size(); ++t) {
      if (one[t].has_value() != many[t].has_value()) {
        ++differing;
        continue;
      }
      if (!one[t]) continue;
      for (std::size_t k = 0; k < 3; ++k) {
        const Vec3<float>& a = (*one[t])[k];
        const Vec3<float>& b = (*many[t])[k];
        differing += a.x != b.x || a.y != b.y || a.z != b.z;
      }
    }
    EXPECT_EQ(differing, 0u) << threads << " threads";
  }
}

TEST(VertexNormals, AFlatGridsNormalsAreThePlanes) {
  // A 12 x 12 grid in a tilted plane: p = o + i u + j v.
  const Vec3<double> o{0.3, -0.2, 1.1}, u{0.8, 0.1, -0.3}, v{-0.2, 0.7, 0.4};
  const Vec3<double> n = cross(u, v);
  const Vec3<double> plane = unit(n.x, n.y, n.z);
  Mesh m;
  constexpr std::uint32_t kSide = 13;
  for (std::uint32_t j = 0; j < kSide; ++j) {
    for (std::uint32_t i = 0; i < kSide; ++i) {
      const Vec3<double> p = o + double(i) * u + double(j) * v;
      m.positions.push_back({float(p.x), float(p.y), float(p.z)});
    }
  }
  for (std::uint32_t j = 0; j + 1 < kSide; ++j) {
    for (std::uint32_t i = 0; i + 1 < kSide; ++i) {
      const std::uint32_t a = j * kSide + i;
      m.triangles.push_back({a, a + 1, a + kSide + 1});
      m.triangles.push_back({a, a + kSide + 1, a + kSide});
    }
  }
  for (const double crease : {1.0, 60.0, 180.0}) {
    const Normals normals = normals_of(m.positions, m.triangles, crease);
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
      for (std::size_t k = 0; k < 3; ++k) {
        // A triangle without normals shades with its face normal.
        const Vec3<double> f = face_normal(m.positions, m.triangles[t]);
        const Vec3<float> shading = normals[t] ? (*normals[t])[k] : Vec3<float>{float(f.x), float(f.y), float(f.z)};
        EXPECT_LT(degrees_between(shading, plane), 1e-4) << crease << " " << t << " " << k;
      }
    }
  }
}

TEST(VertexNormals, TheWeightIsTheCornerAngleNotTheFaceCountOrArea) {
  // Vertex 0 at the origin; face A (0, 1, 2) in z = 0 with a right angle
  // there, face B (0, 2, 3) with a right angle there too, normal (1, 0, 1)/√2.
  // Splitting A at M = (0.25, 0.75, 0) into two triangles of unequal
  // angles must not change vertex 0's normal.
  const std::vector<Vec3<float>> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 1}, {0.25f, 0.75f, 0}};
  const std::vector<TriangleIndices> whole = {{0, 1, 2}, {0, 2, 3}};
  const std::vector<TriangleIndices> split = {{0, 1, 4}, {0, 4, 2}, {0, 2, 3}};
  const Normals a = normals_of(p, whole, 180.0);
  const Normals b = normals_of(p, split, 180.0);
  ASSERT_TRUE(a[0].has_value() && a[1].has_value() && b[2].has_value() && b[0].has_value() && b[1].has_value());
  // Equal corner angles (90 degrees each): the mean of the two unit normals.
  const Vec3<double> expected = unit(1.0 / std::sqrt(2.0), 0.0, 1.0 + 1.0 / std::sqrt(2.0));
  for (const Vec3<float>& n : {(*a[0])[0], (*a[1])[0], (*b[0])[0], (*b[1])[0], (*b[2])[0]}) {
    EXPECT_LT(degrees_between(n, expected), 1e-5);
  }
  // Weighted by face count (A twice) or by area (B is larger), it would be
  // these, which are far from it:
  EXPECT_GT(degrees_between((*b[2])[0], unit(1.0 / std::sqrt(2.0), 0.0, 2.0 + 1.0 / std::sqrt(2.0))), 3.0);
  EXPECT_GT(degrees_between((*b[2])[0], unit(0.5, 0.0, 1.0)), 3.0);
}

TEST(VertexNormals, DegenerateFacesContributeNothingAndStayFaceted) {
  // Two faces of a roof (normals 15 degrees either side of +z, 30 apart), plus a zero-area face
  // (collinear) and one naming a vertex twice, both at the shared vertices.
  const std::vector<Vec3<float>> p = {{0, 0, 0}, {0, 1, 0}, {1, 0, -0.26794919f}, {-1, 0, -0.26794919f}, {0, 2, 0}};
  const std::vector<TriangleIndices> roof = {{0, 2, 1}, {0, 1, 3}};
  std::vector<TriangleIndices> with_degenerate = roof;
  with_degenerate.push_back({0, 1, 4});
  with_degenerate.push_back({0, 1, 1});
  const Normals clean = normals_of(p, roof, 60.0);
  const Normals dirty = normals_of(p, with_degenerate, 60.0);
  ASSERT_TRUE(clean[0].has_value());
  EXPECT_FALSE(dirty[2].has_value());
  EXPECT_FALSE(dirty[3].has_value());
  for (std::size_t t = 0; t < 2; ++t) {
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_EQ((*clean[t])[k].x, (*dirty[t])[k].x);
      EXPECT_EQ((*clean[t])[k].y, (*dirty[t])[k].y);
      EXPECT_EQ((*clean[t])[k].z, (*dirty[t])[k].z);
    }
  }
  // The shared edge's corners get the bisector, +z up to rounding.
  EXPECT_LT(degrees_between((*clean[0])[0], {0.0, 0.0, 1.0}), 1e-5);
  // Below the 30 degrees between them, both stay faceted.
  for (const auto& n : normals_of(p, roof, 29.0)) EXPECT_FALSE(n.has_value());
}

TEST(VertexNormals, AVertexOfMoreThanTheValenceBoundKeepsItsFaceNormals) {
  // A cone's apex shared by kMaxSmoothedValence + 1 triangles: the apex
  // corners keep their face normals, the rim corners are smoothed.
  const std::uint32_t n = std::uint32_t(kMaxSmoothedValence + 1);
  std::vector<Vec3<float>> p = {{0, 1, 0}};
  std::vector<TriangleIndices> fan;
  for (std::uint32_t s = 0; s < n; ++s) {
    const double phi = 2.0 * std::numbers::pi * s / n;
    p.push_back({float(std::cos(phi)), 0.f, float(std::sin(phi))});
    fan.push_back({0, 1 + (s + 1) % n, 1 + s});
  }
  const Normals normals = normals_of(p, fan, 60.0);
  for (std::size_t t = 0; t < fan.size(); ++t) {
    ASSERT_TRUE(normals[t].has_value());
    const Vec3<double> f = face_normal(p, fan[t]);
    EXPECT_LT(degrees_between((*normals[t])[0], f), 1e-5);
    EXPECT_GT(degrees_between((*normals[t])[1], f), 0.1);
  }
  fan.pop_back();  // at the bound, the apex is smoothed too (but for the open seam)
  const Normals bounded = normals_of(p, fan, 60.0);
  EXPECT_GT(degrees_between((*bounded[n / 2])[0], face_normal(p, fan[n / 2])), 1.0);
}

TEST(VertexNormals, BadArgumentsThrow) {
  const Mesh m = cube();
  for (const double crease : {-1.0, 180.5, std::numeric_limits<double>::quiet_NaN(),
                              std::numeric_limits<double>::infinity()}) {
    EXPECT_THROW(normals_of(m.positions, m.triangles, crease), std::invalid_argument) << crease;
  }
  std::vector<TriangleIndices> out_of_range = m.triangles;
  out_of_range.push_back({0, 1, 8});
  EXPECT_THROW(normals_of(m.positions, out_of_range, 60.0), std::invalid_argument);
  EXPECT_TRUE(valid_crease_angle(0.0));
  EXPECT_TRUE(valid_crease_angle(180.0));
  // 0 is faceted: nothing at all, even where 180 would smooth.
  for (const auto& n : normals_of(m.positions, m.triangles, 0.0)) EXPECT_FALSE(n.has_value());
}

}  // namespace
}  // namespace quiver
