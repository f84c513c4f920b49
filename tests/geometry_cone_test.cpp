#include <algorithm>
#include <cfloat>
#include <cmath>
#include <iostream>
#include <limits>
#include <numbers>
#include <optional>

#include <gtest/gtest.h>

#include "geometry/kind_streams.h"
#include "tests/support/kernel_checks.h"
#include "tests/support/ray_sampling.h"
#include "tests/support/study_streams.h"

namespace quiver {
namespace {

using testing::RaySampler;

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

ConeSoA cones_of(std::vector<ConeDesc> descs, BuildReport* out = nullptr) {
  BuildReport report;
  ConeSoA soa = build_cones(descs, report);
  if (out) *out = report;
  return soa;
}

Hit<float> closest(const Ray<float>& ray, const ConeSoA& cones) {
  return testing::closest_hit(study_cone_streams<KernelUnit::scalar>(ConeMethod::quadric), ray, cones);
}

// ---- double-precision reference (same surface, straight from the ConeDesc) --

struct Vec3d {
  double x, y, z;
};
Vec3d to_d(const Vec3<float>& v) { return {v.x, v.y, v.z}; }
Vec3d sub(const Vec3d& a, const Vec3d& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
double dotd(const Vec3d& a, const Vec3d& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

struct RefHit {
  double t;  // nearest valid root in (tmin, inf)
  double s;  // axial coordinate of the hit
};

// Nearest root in (tmin, inf) on the slab and on the real nappe, or none.
std::optional<RefHit> reference_hit(const Ray<float>& ray, const ConeDesc& c) {
  const Vec3d b = to_d(c.base);
  const Vec3d axis = sub(to_d(c.apex), b);
  const double h = std::sqrt(dotd(axis, axis));
  const Vec3d a{axis.x / h, axis.y / h, axis.z / h};
  const double r0 = std::fabs(c.base_radius), k = (std::fabs(c.apex_radius) - r0) / h;
  const Vec3d w = sub(to_d(ray.origin), b), d = to_d(ray.direction);
  const double wa = dotd(w, a), da = dotd(d, a), big_r = r0 + k * wa;
  const double qa = dotd(d, d) - da * da - k * k * da * da;
  const double qb = dotd(w, d) - wa * da - big_r * k * da;
  const double qc = dotd(w, w) - wa * wa - big_r * big_r;
  const double disc = qb * qb - qa * qc;
  if (disc < 0) return std::nullopt;
  const double q = -(qb + std::copysign(std::sqrt(disc), qb));
  std::optional<RefHit> best;
  for (double t : {qa != 0 ? q / qa : kNaN, q != 0 ? qc / q : kNaN}) {
    const double s = wa + t * da;
    if (t > ray.tmin && s >= 0 && s <= h && r0 + k * s >= 0 && (!best || t < best->t)) best = RefHit{t, s};
  }
  return best;
}

// ---- analytic cases ---------------------------------------------------------

// Unit cylinder along +z from z = 0 to z = 2.
const ConeDesc kCylinder{{0, 0, 0}, 1.f, {0, 0, 2}, 1.f};
// Cone along +z: radius 2 at z = 0 shrinking to 0 at z = 2 (slope -1).
const ConeDesc kCone{{0, 0, 0}, 2.f, {0, 0, 2}, 0.f};

TEST(ConeKernel, CylinderHitFromTheSide) {
  const Hit<float> h = closest({{-5, 0, 1}, {1, 0, 0}, 0.f, kInf}, cones_of({kCylinder}));
  ASSERT_EQ(h.id, 0);
  EXPECT_FLOAT_EQ(h.t, 4.f);
  EXPECT_FLOAT_EQ(h.ng.x, -1.f);  // radial, length r = 1
  EXPECT_FLOAT_EQ(h.ng.y, 0.f);
  EXPECT_FLOAT_EQ(h.ng.z, 0.f);
  EXPECT_FLOAT_EQ(h.u, 0.5f);  // s / h
  EXPECT_EQ(h.v, 0.f);
}

TEST(ConeKernel, ConeHitFromTheSide) {
  // At z = 1 the radius is 1: hit at x = -1, t = 4; ng = radial - k r a = (-1, 0, 1).
  const Hit<float> h = closest({{-5, 0, 1}, {2, 0, 0}, 0.f, kInf}, cones_of({kCone}));
  ASSERT_EQ(h.id, 0);
  EXPECT_FLOAT_EQ(h.t, 2.f);  // direction length 2: t in its units
  EXPECT_FLOAT_EQ(h.ng.x, -1.f);
  EXPECT_NEAR(h.ng.y, 0.f, 1e-7f);
  EXPECT_FLOAT_EQ(h.ng.z, 1.f);
  EXPECT_FLOAT_EQ(h.u, 0.5f);
}

TEST(ConeKernel, RayAlongTheAxisInsideACylinderMisses) {
  const ConeSoA cyl = cones_of({kCylinder});
  EXPECT_EQ(closest({{0, 0, 1}, {0, 0, 1}, 0.f, kInf}, cyl).id, kNoHit);
  EXPECT_EQ(closest({{0.5f, 0.3f, -3}, {0, 0, 1}, 0.f, kInf}, cyl).id, kNoHit);  // in through one end, out the other
  EXPECT_EQ(closest({{0, 0, 5}, {0, 0, -2}, 0.f, kInf}, cyl).id, kNoHit);
  EXPECT_EQ(closest({{1, 0, -1}, {0, 0, 1}, 0.f, kInf}, cyl).id, kNoHit);  // the line lies on the surface
  EXPECT_EQ(closest({{3, 0, -1}, {0, 0, 1}, 0.f, kInf}, cyl).id, kNoHit);  // outside
  // A tilted cylinder, ray direction exactly its stored axis.
  const ConeSoA tilted = cones_of({{{1, 2, 3}, 0.5f, {4, -2, 5}, 0.5f}});
  const Vec3<float> a{tilted.ax[0], tilted.ay[0], tilted.az[0]};
  for (float along : {-3.f, 0.f, 1.f}) {
    EXPECT_EQ(closest({Vec3<float>{1.1f, 2.f, 3.f} + a * along, a, 0.f, kInf}, tilted).id, kNoHit);
  }
}

TEST(ConeKernel, RayFromInsideHitsTheInnerWall) {
  const Hit<float> h = closest({{0, 0, 1}, {1, 0, 0}, 0.f, kInf}, cones_of({kCylinder}));
  ASSERT_EQ(h.id, 0);
  EXPECT_FLOAT_EQ(h.t, 1.f);
  EXPECT_FLOAT_EQ(h.ng.x, 1.f);  // outward, not flipped toward the ray
}

TEST(ConeKernel, RayThroughTheOpenEndHitsTheFarInnerWall) {
  // x = -3 + t, z = 5 - t: near root t = 2 is at z = 3 (above the top), far root t = 4 at z = 1.
  const Hit<float> h = closest({{-3, 0, 5}, {1, 0, -1}, 0.f, kInf}, cones_of({kCylinder}));
  ASSERT_EQ(h.id, 0);
  EXPECT_FLOAT_EQ(h.t, 4.f);
  EXPECT_FLOAT_EQ(h.ng.x, 1.f);
  EXPECT_FLOAT_EQ(h.u, 0.5f);
}

TEST(ConeKernel, RayPastTheOpenEndsMisses) {
  const ConeSoA cyl = cones_of({kCylinder});
  EXPECT_EQ(closest({{-3, 0, 5}, {1, 0, 0}, 0.f, kInf}, cyl).id, kNoHit);      // above the top
  EXPECT_EQ(closest({{-3, 0, -0.1f}, {1, 0, 0}, 0.f, kInf}, cyl).id, kNoHit);  // just below the base
  // Through both ends without touching the wall: the wall roots are at z = 45 and z = -155.
  EXPECT_EQ(closest({{0.5f, 0, -5}, {0.01f, 0, 1}, 0.f, kInf}, cyl).id, kNoHit);
  // Both roots outside the slab, one on each side.
  EXPECT_EQ(closest({{-2, 0, -3.5f}, {1, 0, 3}, 0.f, kInf}, cyl).id, kNoHit);  // z = -0.5 at x = -1, 5.5 at x = 1
}

TEST(ConeKernel, MirroredNappeIsRejected) {
  // Radius 1 - z on [0, 1]; the mirrored nappe has radius z - 1 above z = 1.
  const ConeSoA cone = cones_of({{{0, 0, 0}, 1.f, {0, 0, 1}, 0.f}});
  EXPECT_EQ(closest({{-5, 0, 3}, {1, 0, 0}, 0.f, kInf}, cone).id, kNoHit);  // crosses only the mirror, x = -2, 2
  // Down at x = 0.5: the mirror at z = 1.5 is skipped, the real nappe at z = 0.5 is hit from inside.
  const Hit<float> h = closest({{0.5f, 0, 5}, {0, 0, -1}, 0.f, kInf}, cone);
  ASSERT_EQ(h.id, 0);
  EXPECT_FLOAT_EQ(h.t, 4.5f);
  EXPECT_FLOAT_EQ(h.ng.x, 0.5f);  // radial (0.5, 0, 0) - k r a = (0.5, 0, 0.5)
  EXPECT_FLOAT_EQ(h.ng.z, 0.5f);
}

TEST(ConeKernel, RayParallelToAGeneratorLineTakesTheLinearRoot) {
  // Slope -1 cone; direction (-1, 0, 1) is parallel to its +x generator, so A = 0.
  const ConeSoA cone = cones_of({{{0, 0, 0}, 1.f, {0, 0, 1}, 0.f}});
  const Hit<float> h = closest({{0.5f, 0, -0.5f}, {-1, 0, 1}, 0.f, kInf}, cone);
  ASSERT_EQ(h.id, 0);
  EXPECT_FLOAT_EQ(h.t, 1.f);  // (-0.5, 0, 0.5), where the radius is 0.5
  EXPECT_FLOAT_EQ(h.ng.x, -0.5f);
  EXPECT_FLOAT_EQ(h.ng.z, 0.5f);
  // Along the generator line itself: on the surface everywhere, A = B = C = 0: a miss.
  EXPECT_EQ(closest({{2, 0, -1}, {-1, 0, 1}, 0.f, kInf}, cone).id, kNoHit);
}

TEST(ConeKernel, AxisRayThroughTheApexGetsTheTipNormal) {
  // Radius 1 - z / 2: the axis ray from below reaches the apex exactly at t = 7.
  const ConeSoA cone = cones_of({{{0, 0, 0}, 1.f, {0, 0, 2}, 0.f}});
  const Hit<float> h = closest({{0, 0, -5}, {0, 0, 1}, 0.f, kInf}, cone);
  ASSERT_EQ(h.id, 0);
  EXPECT_EQ(h.t, 7.f);
  EXPECT_EQ(h.ng.x, 0.f);
  EXPECT_EQ(h.ng.y, 0.f);
  EXPECT_EQ(h.ng.z, 1.f);  // radial - k r a is 0 there: the axis out of the tip
  EXPECT_EQ(h.u, 1.f);
}

TEST(ConeKernel, ExactlyTangentRayGivesNoNaN) {
  // The line x = 1 touches the unit cylinder along y = 0: a double root at t = 5.
  for (const Ray<float>& ray : {Ray<float>{{1, -5, 1}, {0, 1, 0}, 0.f, kInf}, Ray<float>{{-1, -3, -3}, {0, 0.6f, 0.8f}, 0.f, kInf}}) {
    const Hit<float> h = closest(ray, cones_of({kCylinder}));
    if (h.id == kNoHit) continue;
    EXPECT_NEAR(h.t, 5.f, 1e-3f);
    EXPECT_TRUE(std::isfinite(h.ng.x) && std::isfinite(h.ng.y) && std::isfinite(h.ng.z));
    EXPECT_GT(dot(h.ng, h.ng), 0.f);
  }
}

TEST(ConeKernel, RespectsOpenInterval) {
  const ConeSoA cyl = cones_of({kCylinder});
  EXPECT_EQ(closest({{-5, 0, 1}, {1, 0, 0}, 0.f, 4.f}, cyl).id, kNoHit);  // t == tmax
  const Hit<float> far = closest({{-5, 0, 1}, {1, 0, 0}, 4.f, kInf}, cyl);  // t == tmin: the far wall
  ASSERT_EQ(far.id, 0);
  EXPECT_FLOAT_EQ(far.t, 6.f);
  EXPECT_EQ(closest({{-5, 0, 1}, {-1, 0, 0}, 0.f, kInf}, cyl).id, kNoHit);  // behind
}

TEST(ConeKernel, ClosestOfSeveralAndTieGoesToFirst) {
  const ConeSoA cones = cones_of({{{0, 0, 0}, 1.f, {0, 0, 2}, 1.f}, {{0, 0, 0}, 3.f, {0, 0, 2}, 3.f},
                                  {{0, 0, -1}, 3.f, {0, 0, 3}, 3.f}});
  const Hit<float> h = closest({{-5, 0, 1}, {1, 0, 0}, 0.f, kInf}, cones);
  EXPECT_EQ(h.id, 1);
  EXPECT_FLOAT_EQ(h.t, 2.f);
}

TEST(ConeKernel, NegativeRadiiMeanInsideVisible) {
  BuildReport report;
  const ConeSoA cyl = cones_of({{{0, 0, 0}, -1.f, {0, 0, 2}, -1.f}}, &report);
  ASSERT_EQ(report.kept, 1u);
  const Hit<float> h = closest({{-5, 0, 1}, {1, 0, 0}, 0.f, kInf}, cyl);
  ASSERT_EQ(h.id, 0);
  EXPECT_FLOAT_EQ(h.t, 4.f);      // same surface as radius 1
  EXPECT_FLOAT_EQ(h.ng.x, 1.f);   // normal points inward
}

// ---- builder ----------------------------------------------------------------

// The texture footprint: v runs along the axis over the height (a step up
// the wall of a quarter of it is a quarter of v), u around it (a step
// around the rim of an eighth of its circumference is an eighth of u), each
// unchanged by a step along the other.
TEST(ConeMapping, TheFootprintOfVFollowsTheHeightAndOfUTheAngle) {
  BuildReport report;
  const std::vector<ConeDesc> descs{{{0.f, 0.f, 0.f}, 2.f, {0.f, 4.f, 0.f}, 2.f}};  // a cylinder 4 high, radius 2
  const ConeSoA store = build_cones(descs, report);
  ASSERT_EQ(store.count, 1u);
  const Hit<float> hit{6.f, 0.5f, 0.f, {1.f, 0.f, 0.f}, 0};
  const float arc = 2.f * std::numbers::pi_v<float> * 2.f / 8.f;
  const MappingQuery query{hit, 0, true, true, {2.f, 2.f, 0.f}, {{0.f, 1.f, 0.f}, {0.f, 0.f, arc}}, nullptr, nullptr};
  SurfaceMapping mapped{};
  map_surface(store, query, mapped);
  EXPECT_FLOAT_EQ(mapped.dv[0], 0.25f);
  EXPECT_NEAR(mapped.dv[1], 0.f, 1e-6f);
  EXPECT_NEAR(mapped.du[0], 0.f, 1e-6f);
  EXPECT_NEAR(std::fabs(mapped.du[1]), 0.125f, 1e-5f);
}

TEST(ConeBuild, DropsDegenerateAndNonFinite) {
  BuildReport report;
  const ConeSoA soa = cones_of({{{kNaN, 0, 0}, 1.f, {0, 0, 1}, 1.f},
                                {{0, 0, 0}, kInf, {0, 0, 1}, 1.f},
                                {{0, 0, 0}, 1.f, {0, 0, 1}, kNaN},
                                {{-3e38f, 0, 0}, 1.f, {3e38f, 0, 0}, 1.f},  // axis length overflows
                                {{1, 2, 3}, 1.f, {1, 2, 3}, 1.f},          // zero axis
                                {{0, 0, 0}, 0.f, {0, 0, 1}, -0.f},         // both radii zero
                                {{0, 0, 0}, 1.f, {0, 0, 1}, -1.f},         // mixed signs
                                {{0, 0, 0}, 1e-30f, {0, 0, 1}, 1e-30f},    // radius^2 underflows
                                {{0, 0, 0}, 1e20f, {0, 0, 1}, 1e20f},      // radius^2 overflows
                                {{0, 0, 0}, 0.f, {0, 0, 1e-30f}, 1.f},     // slope^2 overflows
                                {{0, 0, 0}, 1.f, {0, 0, 0}, 1.f},          // zero axis, equal points
                                {{1, 1, 1}, 2.f, {1, 1, 5}, 0.f}},         // kept: a cone
                               &report);
  EXPECT_EQ(soa.size(), 1u);
  EXPECT_EQ(report.kept, 1u);
  EXPECT_EQ(report.dropped_non_finite, 4u);
  EXPECT_EQ(report.dropped_degenerate, 7u);
  EXPECT_FLOAT_EQ(soa.az[0], 1.f);  // unit axis
  EXPECT_FLOAT_EQ(soa.height[0], 4.f);
  EXPECT_FLOAT_EQ(soa.radius0[0], 2.f);
  EXPECT_FLOAT_EQ(soa.slope[0], -0.5f);
  EXPECT_EQ(soa.facing[0], 1.f);
  // Padding copies the last real cone: finite everywhere.
  ASSERT_EQ(soa.bx.size() % kMaxLanes, 0u);
  for (const AlignedFloats* c : {&soa.bx, &soa.ax, &soa.height, &soa.radius0, &soa.slope, &soa.facing}) {
    for (float v : *c) EXPECT_TRUE(std::isfinite(v));
  }
}

TEST(ConeBuild, NegativeRadiiKeptWithAbsoluteValuesAndInwardFacing) {
  BuildReport report;
  const ConeSoA soa = cones_of({{{0, 0, 0}, -2.f, {0, 0, 1}, 0.f}, {{0, 0, 0}, 0.f, {0, 0, 1}, -2.f}}, &report);
  ASSERT_EQ(report.kept, 2u);
  EXPECT_EQ(soa.radius0[0], 2.f);
  EXPECT_EQ(soa.slope[0], -2.f);
  EXPECT_EQ(soa.radius0[1], 0.f);
  EXPECT_EQ(soa.slope[1], 2.f);
  EXPECT_EQ(soa.facing[0], -1.f);
  EXPECT_EQ(soa.facing[1], -1.f);
}

// ---- stability --------------------------------------------------------------

std::vector<ConeDesc> random_cones(RaySampler& s, std::size_t n, const Vec3<float>& center, float spread) {
  std::vector<ConeDesc> descs;
  const Vec3<float> reach{spread, spread, spread};
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3<float> base = s.in_box(center - reach, center + reach);
    const Vec3<float> apex = base + s.unit_direction() * s.uniform(0.5f, 3.f);
    const float r0 = s.uniform(0.2f, 1.5f);
    const int shape = static_cast<int>(i % 3);  // cylinder, truncated cone, full cone
    descs.push_back({base, r0, apex, shape == 0 ? r0 : (shape == 1 ? s.uniform(0.1f, 2.f) : 0.f)});
  }
  return descs;
}

// A point on the cone's wall at axial fraction f and angle phi, with the
// outward unit normal there.
struct SurfacePoint {
  Vec3<float> p, n;
};
SurfacePoint surface_point(const ConeDesc& c, float f, float phi) {
  const Vec3d axis = sub(to_d(c.apex), to_d(c.base));
  const double h = std::sqrt(dotd(axis, axis));
  const Vec3<float> a{float(axis.x / h), float(axis.y / h), float(axis.z / h)};
  const Vec3<float> helper = std::fabs(a.x) < 0.6f ? Vec3<float>{1, 0, 0} : Vec3<float>{0, 1, 0};
  const Vec3<float> e1 = normalize(cross(a, helper)), e2 = cross(a, e1);
  const Vec3<float> radial = e1 * std::cos(phi) + e2 * std::sin(phi);
  const float r = c.base_radius + (c.apex_radius - c.base_radius) * f;
  const float k = (c.apex_radius - c.base_radius) / float(h);
  return {c.base + a * (float(h) * f) + radial * r, normalize(radial - a * k)};
}

TEST(ConeStability, GrazingTangentRaysGiveNoNaNAndAgreeAwayFromTheSilhouette) {
  // Lines in the tangent plane at a wall point, moved off it along the normal
  // by up to 1e-4: outward they miss (the solid is convex), inward they cut
  // the wall near the point (or far away for directions along a generator).
  RaySampler s(21);
  const std::vector<ConeDesc> descs = random_cones(s, 6, {0, 0, 0}, 3.f);
  std::size_t hits = 0, decided = 0, agreed = 0;
  for (const ConeDesc& c : descs) {
    const ConeSoA one = cones_of({c});
    ASSERT_EQ(one.size(), 1u);
    for (int i = 0; i < 2000; ++i) {
      const SurfacePoint sp = surface_point(c, s.uniform(0.05f, 0.95f), s.uniform(0.f, 6.2831853f));
      const Vec3<float> tangent = normalize(cross(sp.n, s.unit_direction()));
      const float offset = s.uniform(-1e-4f, 1e-4f);
      const Ray<float> ray{sp.p + sp.n * offset - tangent * s.uniform(1.f, 10.f), tangent, 0.f, kInf};
      const Hit<float> h = closest(ray, one);
      if (h.id != kNoHit) {
        ++hits;
        EXPECT_TRUE(std::isfinite(h.t) && h.t > 0.f);
        EXPECT_TRUE(std::isfinite(h.ng.x) && std::isfinite(h.ng.y) && std::isfinite(h.ng.z));
        EXPECT_GT(dot(h.ng, h.ng), 0.f);
        EXPECT_TRUE(h.u >= 0.f && h.u <= 1.f) << h.u;
      }
      // Agreement with the double reference when the line is clearly off the tangent.
      if (std::fabs(offset) > 1e-5f) {
        ++decided;
        agreed += (h.id != kNoHit) == reference_hit(ray, c).has_value();
      }
    }
  }
  EXPECT_GT(hits, 1000u);  // the test exercises hits
  // Only a cut at a slab end (s = 0 or h to within rounding) may flip the verdict.
  std::cout << "[ cone grazing ] " << hits << " hits; " << agreed << " of " << decided
            << " clear-cut rays agree with the double reference\n";
  EXPECT_GE(double(agreed), 0.999 * double(decided)) << agreed << " of " << decided;
}

TEST(ConeStability, RaysParallelToTheAxisNeverHitACylinderAndHitConesWhereTheRadiusMatches) {
  RaySampler s(23);
  const std::vector<ConeDesc> descs = random_cones(s, 9, {0, 0, 0}, 3.f);
  const ConeSoA all = cones_of(descs);
  ASSERT_EQ(all.size(), descs.size());
  std::size_t cone_hits = 0;
  for (std::size_t ci = 0; ci < descs.size(); ++ci) {
    const ConeSoA one = cones_of({descs[ci]});
    const Vec3<float> a{one.ax[0], one.ay[0], one.az[0]};
    const bool cylinder = descs[ci].base_radius == descs[ci].apex_radius;
    for (int i = 0; i < 500; ++i) {
      // From on the surface, on the axis, inside and outside; both senses;
      // power-of-two scales keep the direction exactly parallel to the axis.
      const float f = s.uniform(-1.f, 2.f);
      const SurfacePoint sp = surface_point(descs[ci], f, s.uniform(0.f, 6.2831853f));
      const Vec3<float> on_axis = descs[ci].base + (descs[ci].apex - descs[ci].base) * f;
      const float off = std::max(descs[ci].base_radius, descs[ci].apex_radius) * s.uniform(-1.f, 1.f);
      const Vec3<float> origin = (i % 5 == 0) ? sp.p : (i % 5 == 1 ? on_axis : sp.p + sp.n * off);
      const Vec3<float> dir = a * std::ldexp(i % 2 ? -1.f : 1.f, s.uniform_int(-10, 10));
      const Ray<float> ray{origin, dir, 0.f, kInf};
      const Hit<float> h = closest(ray, one);
      if (cylinder) {
        EXPECT_EQ(h.id, kNoHit) << "cylinder " << ci << " ray " << i;
        continue;
      }
      if (h.id == kNoHit) continue;
      ++cone_hits;
      EXPECT_TRUE(std::isfinite(h.t) && std::isfinite(h.ng.x) && std::isfinite(h.ng.y) && std::isfinite(h.ng.z));
      EXPECT_GT(dot(h.ng, h.ng), 0.f);
      const auto ref = reference_hit(ray, descs[ci]);
      if (ref) {
        EXPECT_NEAR(h.t * length(dir), ref->t * length(dir), 1e-4 * (1 + ref->t * length(dir)));
      }
    }
  }
  EXPECT_GT(cone_hits, 300u);
}

// Relative t error vs the double reference, in float epsilons, of the kernel
// and of the textbook float formula (A = d.d - (1 + k^2) da^2, B, C from raw
// dot products of w = o - b, disc = B^2 - A C, t = (-B - sqrt(disc)) / A).
struct ErrorStats {
  double max_eps = 0;
  std::size_t misses = 0;  // reference hits the kernel lost
};

float naive_float_t(const Ray<float>& ray, const ConeDesc& c) {
  const Vec3<float> axis = c.apex - c.base;
  const float h = length(axis);
  const Vec3<float> a = axis / h;
  const float k = (c.apex_radius - c.base_radius) / h;
  const Vec3<float> w = ray.origin - c.base, d = ray.direction;
  const float wa = dot(w, a), da = dot(d, a), big_r = c.base_radius + k * wa;
  const float qa = dot(d, d) - (1 + k * k) * da * da;
  const float qb = dot(w, d) - wa * da - big_r * k * da;
  const float qc = dot(w, w) - wa * wa - big_r * big_r;
  const float disc = qb * qb - qa * qc;
  return disc < 0 ? kNaN : (-qb - std::sqrt(disc)) / qa;
}

TEST(ConeAccuracy, FarFromOriginConesAndCylindersMatchTheDoubleReference) {
  // Cylinders and cones near (1e5, 1e5, 1e5); rays from a camera 20 units away
  // (local) and from the world origin (distance 1.7e5) aimed at front-facing
  // wall points away from the rims.
  RaySampler s(29);
  const Vec3<float> far_center{1e5f, 1e5f, 1e5f};
  const std::vector<ConeDesc> descs = random_cones(s, 8, far_center, 2.f);
  ErrorStats robust_local, robust_origin, naive_origin;
  std::size_t naive_lost = 0, trials = 0, local_trials = 0;
  for (std::size_t ci = 0; ci < descs.size(); ++ci) {
    const ConeSoA one = cones_of({descs[ci]});
    for (int i = 0; i < 1000; ++i) {
      const SurfacePoint sp = surface_point(descs[ci], s.uniform(0.2f, 0.8f), s.uniform(0.f, 6.2831853f));
      for (bool from_origin : {false, true}) {
        const Vec3<float> eye = from_origin ? Vec3<float>{0, 0, 0} : far_center + s.unit_direction() * 20.f;
        const Ray<float> ray = s.toward(eye, sp.p);
        const Vec3<float> dir = normalize(ray.direction);
        if (dot(dir, sp.n) > -0.2f) continue;  // front-facing, not grazing
        const auto ref = reference_hit(ray, descs[ci]);
        if (!ref || std::fabs(ref->t - 1.0) > 1e-3) continue;  // the aimed point is the first hit
        ErrorStats& st = from_origin ? robust_origin : robust_local;
        const Hit<float> h = closest(ray, one);
        if (h.id == kNoHit) {
          ++st.misses;
          continue;
        }
        st.max_eps = std::max(st.max_eps, std::fabs(h.t - ref->t) / ref->t / FLT_EPSILON);
        local_trials += !from_origin;
        if (from_origin) {
          ++trials;
          const float tn = naive_float_t(ray, descs[ci]);
          if (!std::isfinite(tn)) {
            ++naive_lost;
          } else {
            naive_origin.max_eps = std::max(naive_origin.max_eps, std::fabs(tn - ref->t) / ref->t / FLT_EPSILON);
          }
        }
      }
    }
  }
  ASSERT_GT(trials, 1000u);
  ASSERT_GT(local_trials, 1000u);
  RecordProperty("robust_local_max_eps", std::to_string(robust_local.max_eps));
  RecordProperty("robust_origin_max_eps", std::to_string(robust_origin.max_eps));
  RecordProperty("naive_origin_max_eps", std::to_string(naive_origin.max_eps));
  std::cout << "[ cone 1e5 ] kernel: local max " << robust_local.max_eps << " eps over " << local_trials
            << " rays, from origin max " << robust_origin.max_eps << " eps over " << trials
            << "; textbook float from origin: max " << naive_origin.max_eps << " eps, lost " << naive_lost
            << " of " << trials << "\n";
  EXPECT_EQ(robust_local.misses, 0u);
  EXPECT_EQ(robust_origin.misses, 0u);
  // Without the origin shift: 38 eps local (cones seen from beyond the apex), 3.6 from the origin.
  EXPECT_LT(robust_local.max_eps, 2.0);
  EXPECT_LT(robust_origin.max_eps, 2.0);
  // The textbook formula loses hits or accuracy from the origin: disc = B^2 - A C
  // cancels terms ~|w|^2 |d|^2 down to ~r^2 |d|^2.
  EXPECT_TRUE(naive_lost > 0 || naive_origin.max_eps > 100.0);
}

// ---- every width equals the scalar reference --------------------------------

template <class W>
class ConeWidths : public testing::UnitTest<W> {};
TYPED_TEST_SUITE(ConeWidths, testing::KernelUnits);

TYPED_TEST(ConeWidths, MatchesScalarBitForBit) {
  RaySampler s(7);
  std::vector<ConeDesc> descs = random_cones(s, 11, {0, 0, 0}, 4.f);  // not a multiple of any width
  const ConeSoA cones = cones_of(descs);
  ASSERT_EQ(cones.size(), 11u);
  std::vector<Ray<float>> rays = testing::adversarial_rays(s, 50'003, {0, 0, 0}, 5.f);
  for (int i = 0; i < 38'000; ++i) {
    const ConeDesc& c = descs[s.uniform_int(0, 10)];
    const Vec3<float> target = surface_point(c, s.uniform(-0.1f, 1.1f), s.uniform(0.f, 6.2831853f)).p;
    rays.push_back(s.toward(s.in_box({-9, -9, -9}, {9, 9, 9}), target));
  }
  for (int i = 0; i < 12'000; ++i) {  // kind-specific: grazing, axis-parallel, from inside, through the apex
    const std::size_t ci = static_cast<std::size_t>(s.uniform_int(0, 10));
    const ConeDesc& c = descs[ci];
    const Vec3<float> a{cones.ax[ci], cones.ay[ci], cones.az[ci]};
    const SurfacePoint sp = surface_point(c, s.uniform(0.f, 1.f), s.uniform(0.f, 6.2831853f));
    switch (i % 4) {
      case 0: {
        const Vec3<float> tangent = cross(sp.n, s.unit_direction()) + sp.n * s.uniform(-1e-6f, 1e-6f);
        rays.push_back({sp.p - tangent * 3.f, tangent, 0.f, kInf});
        break;
      }
      case 1: rays.push_back({sp.p + sp.n * s.uniform(-0.5f, 0.5f) - a * 5.f, a * s.uniform(-2.f, 2.f), 0.f, kInf}); break;
      case 2: rays.push_back({c.base + (c.apex - c.base) * s.uniform(0.1f, 0.9f), s.unit_direction(), 0.f, kInf}); break;
      default: rays.push_back(s.toward(c.apex + s.unit_direction() * 4.f, c.apex)); break;
    }
  }
  RaySoA soa = testing::to_soa(rays);
  ASSERT_NE(rays.size() % 8, 0u);
  ASSERT_GE(rays.size(), 100'000u);
  testing::poison_padding(soa);
  const auto ref =
      testing::expect_streams_match_scalar(study_cone_streams<KernelUnit::scalar>(ConeMethod::quadric),
                                           study_cone_streams<TestFixture::kUnit>(ConeMethod::quadric), soa, cones);
  EXPECT_GT(ref.closest_packets.hit_count(), rays.size() / 4);  // the test exercises hits
}

}  // namespace
}  // namespace quiver

