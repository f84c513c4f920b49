// Pins every stability claim of bench/ACCURACY.md: where each intersector
// method breaks along the stress sweeps (bench/accuracy/stress.h) against the
// double-double oracle, watertightness on closed meshes, and acne against
// scene scale per offset rule. The sweeps run with fewer rays than
// quiver_accuracy (a prefix of the same rays: same seeds), so "never wrong"
// claims carry over and "wrong by" bounds sit where many rays fail.
// Every width gives the same bits (tests/geometry_*_test.cpp), so the
// portable scalar unit stands for all of them.
#include <cmath>
#include <cstdio>
#include <optional>

#include <gtest/gtest.h>

#include "bench/accuracy/closed_meshes.h"
#include "bench/accuracy/measure.h"

namespace quiver::accuracy {
namespace {

constexpr std::size_t kRays = 4000;
constexpr std::optional<KernelUnit> kFloat = KernelUnit::scalar;
constexpr std::optional<KernelUnit> kDouble = std::nullopt;

std::vector<SweepRow> sweep(const char* kind, const char* method, Distribution d, std::optional<KernelUnit> unit) {
  return run_sweep(find_method(kind, method), d, unit, kRays, 1);
}

std::size_t wrong(const ErrorStats& s) { return s.false_miss + s.false_hit; }

// Wrong answers among counted rays at parameters up to `last` (inclusive, sweep order).
std::size_t wrong_through(const std::vector<SweepRow>& rows, double last) {
  std::size_t n = 0;
  for (const SweepRow& r : rows) {
    if (r.built && (r.parameter <= last * 1.0001)) n += wrong(r.stats);
  }
  return n;
}

const SweepRow& at(const std::vector<SweepRow>& rows, double parameter) {
  for (const SweepRow& r : rows) {
    if (std::fabs(r.parameter - parameter) <= 1e-6 * parameter) return r;
  }
  throw std::invalid_argument("no such sweep parameter");
}

TEST(AccuracyFailurePoints, SeedSpheresBreakHundredsOfRadiiAwayRobustOnlyAtTheFloatOriginFloor) {
  for (const char* seed_method : {"algebraic", "geometric"}) {
    const auto rows = sweep("sphere", seed_method, Distribution::distance, kFloat);
    const FailurePoint f = find_failure_point(rows);
    std::printf("[ measured ] sphere/%s distance: first false hit %g, first false miss %g, p99 %.0f ulp at 1e3\n",
                seed_method, f.first_false_hit, f.first_false_miss, at(rows, 1e3).stats.ulp_p99);
    EXPECT_EQ(wrong_through(rows, 31.7), 0u) << seed_method;
    EXPECT_LE(std::fmin(f.first_false_hit, f.first_false_miss), 1e3) << seed_method;
    EXPECT_GT(at(rows, 1e3).stats.ulp_p99, 1000.0) << seed_method;
    EXPECT_GT(at(rows, 1e4).stats.false_miss_rate(), 0.03) << seed_method;  // 22.8% / 19.5% with 20,000 rays
  }
  const auto robust = sweep("sphere", "robust", Distribution::distance, kFloat);
  const FailurePoint f = find_failure_point(robust);
  EXPECT_EQ(wrong_through(robust, 3.17e4), 0u);
  EXPECT_LE(std::fmin(f.first_false_hit, f.first_false_miss), 1e6);  // the float origin floor
  EXPECT_LT(f.worst_relative, 2e-6);
  EXPECT_LE(f.worst_ulp_p99, 4.0);
  // The same formulas in double: robust never wrong through 1e7, the seed's
  // quadratic wrong by 1e7.
  const FailurePoint robust_double = find_failure_point(sweep("sphere", "robust", Distribution::distance, kDouble));
  EXPECT_TRUE(std::isnan(robust_double.first_false_hit) && std::isnan(robust_double.first_false_miss));
  EXPECT_LT(robust_double.worst_relative, 1e-14);
  const auto algebraic_double = sweep("sphere", "algebraic", Distribution::distance, kDouble);
  EXPECT_EQ(wrong_through(algebraic_double, 1e6), 0u);
  EXPECT_GT(wrong(at(algebraic_double, 1e7).stats), 0u);
}

TEST(AccuracyFailurePoints, PlanarKindsAndConesHoldUpToTenThousandSizesAway) {
  struct Expectation {
    const char* kind;
    const char* method;
    double never_wrong_through;
    double max_ulp_p99;
  };
  for (const Expectation& e : {Expectation{"plane", "seed", 1e7, 4.0}, Expectation{"plane", "anchored", 1e7, 4.0},
                               Expectation{"triangle", "moller_trumbore", 1e4, 4.0},
                               Expectation{"triangle", "watertight", 1e4, 4.0}, Expectation{"polygon", "crossing", 1e4, 4.0},
                               Expectation{"cone", "quadric", 1e4, 8.0}}) {
    const auto rows = sweep(e.kind, e.method, Distribution::distance, kFloat);
    const FailurePoint f = find_failure_point(rows);
    EXPECT_EQ(wrong_through(rows, e.never_wrong_through), 0u) << e.kind << "/" << e.method;
    EXPECT_LE(f.worst_ulp_p99, e.max_ulp_p99) << e.kind << "/" << e.method;
    EXPECT_LT(f.worst_relative, 1e-5) << e.kind << "/" << e.method;
  }
}

TEST(AccuracyFailurePoints, EveryMethodIsScaleInvariantFromTinyToHuge) {
  for (const Method& m : kMethods) {
    const auto rows = run_sweep(m, Distribution::size, kFloat, kRays, 1);
    const FailurePoint f = find_failure_point(rows);
    EXPECT_EQ(f.last_built, 1e12) << m.kind_name << "/" << m.name;
    EXPECT_EQ(wrong_through(rows, 1e12), 0u) << m.kind_name << "/" << m.name;
    const bool seed_sphere = m.kind == Kind::sphere && m.name != "robust";
    EXPECT_LE(f.worst_ulp_p99, seed_sphere ? 100.0 : 4.0) << m.kind_name << "/" << m.name;
  }
}

TEST(AccuracyFailurePoints, FarFromTheOriginOnlyTheSeedPlaneOffsetLosesDigits) {
  for (const Method& m : kMethods) {
    const auto rows = run_sweep(m, Distribution::far, kFloat, kRays, 1);
    const FailurePoint f = find_failure_point(rows);
    EXPECT_EQ(wrong_through(rows, 1e7), 0u) << m.kind_name << "/" << m.name;
    if (m.kind == Kind::polygon) {
      // A tilted star polygon is planar in float only near the origin: the builder drops it beyond.
      EXPECT_GE(f.last_built, 1e3);
      EXPECT_LT(f.last_built, 1e7);
    }
    if (m.kind == Kind::plane && m.name == "seed") {
      EXPECT_LT(at(rows, 3.16227766e4).stats.relative_max, 1e-3);
      EXPECT_GT(at(rows, 1e5).stats.relative_max, 1e-3);
    } else if (m.kind == Kind::plane) {  // anchored at the plane's point: as the robust sphere
      EXPECT_LT(f.worst_relative, 1e-5);
      EXPECT_LE(f.worst_ulp_p99, 3.0);
    } else if (m.kind == Kind::sphere && m.name == "robust") {
      EXPECT_LE(f.worst_ulp_p99, 3.0);
    }
  }
}

TEST(AccuracyFailurePoints, GrazingRaysAreDecidedWrongOnlyNearTheSilhouette) {
  const FailurePoint robust = find_failure_point(sweep("sphere", "robust", Distribution::grazing, kFloat));
  const FailurePoint algebraic = find_failure_point(sweep("sphere", "algebraic", Distribution::grazing, kFloat));
  const FailurePoint cone = find_failure_point(sweep("cone", "quadric", Distribution::grazing, kFloat));
  std::printf("[ measured ] wrong answers within %.2g (robust), %.2g (algebraic), %.2g (cone) of the silhouette\n",
              robust.wrong_band, algebraic.wrong_band, cone.wrong_band);
  EXPECT_LT(robust.wrong_band, 1e-6);
  EXPECT_GT(algebraic.wrong_band, 5e-6);
  EXPECT_LT(cone.wrong_band, 1e-6);
  // Rays at small angles to a flat surface: t within 1e-3 down to 1e-4 rad.
  for (const char* method : {"watertight", "moller_trumbore"}) {
    const auto rows = sweep("triangle", method, Distribution::grazing, kFloat);
    EXPECT_LT(at(rows, 1e-3).stats.relative_max, 1e-3) << method;
  }
  EXPECT_LT(at(sweep("triangle", "watertight", Distribution::grazing, kFloat), 1e-4).stats.relative_max, 1e-3);
  EXPECT_LT(at(sweep("plane", "seed", Distribution::grazing, kFloat), 1e-4).stats.relative_max, 1e-3);
  // eps / angle is 6e-4 at 1e-4 rad; the anchored numerator adds the rounding of p - o.
  EXPECT_LT(at(sweep("plane", "anchored", Distribution::grazing, kFloat), 1e-4).stats.relative_max, 1.5e-3);
  EXPECT_LT(at(sweep("polygon", "crossing", Distribution::grazing, kFloat), 1e-4).stats.relative_max, 1e-3);
}

TEST(AccuracyWatertightness, WatertightNeverLeaksMollerTrumboreAndPolygonCrossingDo) {
  const KernelUnit unit = units_by_width().back();
  const Vec3<double> far_center{1000.3, -700.7, 300.1};
  struct MeshCase {
    ClosedMesh mesh;
    Vec3<float> center;
  };
  const MeshCase meshes[] = {
      {box_triangles({-1.3, -0.7, -1.1}, {0.9, 1.6, 1.2}), {-0.2f, 0.45f, 0.05f}},
      {octasphere(2, {0, 0, 0}, {1, 1, 1}, 0.0, 1), {0.f, 0.f, 0.f}},
      {octasphere(2, far_center, {2.7, 1.4, 3.3}, 0.15, 2),
       {float(far_center.x), float(far_center.y), float(far_center.z)}},
  };
  for (const MeshCase& mc : meshes) {
    ASSERT_TRUE(mc.mesh.closed());
    const LeakCount watertight = count_leaks(find_method("triangle", "watertight"), unit, mc.mesh, mc.center, 0.3f, 200'000, 99);
    const LeakCount mt = count_leaks(find_method("triangle", "moller_trumbore"), unit, mc.mesh, mc.center, 0.3f, 200'000, 99);
    EXPECT_EQ(watertight.edge_leaks + watertight.vertex_leaks, 0u);
    EXPECT_GT(mt.edge_leaks + mt.vertex_leaks, 0u);
  }
  // The crossing test's half-open rule is consistent within one plane only:
  // on a box of quads, an edge point can be "outside" in both faces.
  const ClosedMesh quads = box_quads({-1.3, -0.7, -1.1}, {0.9, 1.6, 1.2});
  ASSERT_TRUE(quads.closed());
  const LeakCount crossing = count_leaks(find_method("polygon", "crossing"), unit, quads, {-0.2f, 0.45f, 0.05f}, 0.3f, 30'000, 99);
  EXPECT_GT(crossing.edge_leaks, crossing.edge_rays / 10);
}

TEST(AccuracySelfIntersection, RobustOffsetHasNoAcneAtAnyScaleFixedEpsilonFailsLarge) {
  const KernelUnit unit = units_by_width().back();
  for (const Method& m : kMethods) {
    for (int k = -4; k <= 6; ++k) {
      const double scale = std::pow(10.0, k);
      const AcneCount robust = count_acne(m, unit, scale, OffsetRule::robust, 1000, 5);
      EXPECT_GT(robust.spawned, 200u);
      EXPECT_EQ(robust.rehits, 0u) << m.kind_name << "/" << m.name << " at scale " << scale;
      const AcneCount none = count_acne(m, unit, scale, OffsetRule::zero, 1000, 5);
      EXPECT_GT(none.fraction(), 0.1) << m.kind_name << "/" << m.name << " at scale " << scale;
      const AcneCount epsilon = count_acne(m, unit, scale, OffsetRule::epsilon, 1000, 5);
      if (k <= -2) {
        EXPECT_EQ(epsilon.rehits, 0u) << m.kind_name << "/" << m.name << " at scale " << scale;
      }
      if (k >= 3) {
        EXPECT_GT(epsilon.fraction(), 0.1) << m.kind_name << "/" << m.name << " at scale " << scale;
      }
    }
  }
}

}  // namespace
}  // namespace quiver::accuracy
