// The accuracy study's instruments checked by hand: double-double
// arithmetic, float ulps, the oracle's t, hit/miss and clearance on cases
// computed on paper, and the double-lane evaluation of the kernel templates
// (bench/accuracy/).
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "bench/accuracy/double_double.h"
#include "bench/accuracy/measure.h"
#include "bench/accuracy/oracle.h"

namespace quiver::accuracy {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

Ray<float> ray(Vec3<float> o, Vec3<float> d) { return {o, d, 0.f, kInf}; }

SphereSoA one_sphere(Vec3<float> center, float radius) {
  BuildReport report;
  return build_spheres(std::vector<SphereDesc>{{center, radius}}, report);
}

TEST(AccuracyDoubleDouble, ProductsAndSumsAreExactAndRootsCarry106Bits) {
  // (1 + 2^-30)^2 = 1 + 2^-29 + 2^-60: the last term is below a double's precision.
  const DoubleDouble square = two_product(1.0 + 0x1p-30, 1.0 + 0x1p-30);
  EXPECT_EQ(square.hi, 1.0 + 0x1p-29);
  EXPECT_EQ(square.lo, 0x1p-60);
  const DoubleDouble sum = two_sum(1e16, 1.0);
  EXPECT_EQ(sum.hi + 0.0, 1e16);
  EXPECT_EQ(sum.lo, 1.0);
  const DoubleDouble root2 = sqrt(DoubleDouble(2.0));
  const DoubleDouble residual = root2 * root2 - DoubleDouble(2.0);
  EXPECT_LT(std::fabs(residual.to_double()), 1e-30);
  const DoubleDouble third = DoubleDouble(1.0) / DoubleDouble(3.0);
  EXPECT_LT(std::fabs((third * DoubleDouble(3.0) - DoubleDouble(1.0)).to_double()), 1e-31);
  EXPECT_NE(third.lo, 0.0);  // a plain double division would leave it 0
}

TEST(AccuracyOracle, FloatUlpsAreTheFloatSpacing) {
  EXPECT_EQ(float_ulp(1.0), 0x1p-23);
  EXPECT_EQ(float_ulp(1.99), 0x1p-23);
  EXPECT_EQ(float_ulp(2.0), 0x1p-22);
  EXPECT_EQ(float_ulp(-3.0), 0x1p-22);
  EXPECT_EQ(float_ulp(0.0), double(std::numeric_limits<float>::denorm_min()));
  EXPECT_EQ(ulp_error(1.0 + 0x1p-22, 1.0), 2.0);
  EXPECT_EQ(ulp_error(double(std::nextafter(1e7f, 2e7f)), 1e7), 1.0);
}

TEST(AccuracyOracle, SphereByHand) {
  const SphereSoA unit = one_sphere({0, 0, 0}, 1);
  Reference r = reference(ray({0, 0, -5}, {0, 0, 1}), unit, 0);
  EXPECT_TRUE(r.hit);
  EXPECT_EQ(r.t, 4.0);
  EXPECT_EQ(r.clearance, 1.0);  // the line passes through the center
  r = reference(ray({0, 0, 0}, {0, 0, 2}), unit, 0);  // from inside: the far side, t in units of d
  EXPECT_TRUE(r.hit);
  EXPECT_EQ(r.t, 0.5);
  r = reference(ray({1, 0, -5}, {0, 0, 1}), unit, 0);  // exact tangent
  EXPECT_TRUE(r.hit);
  EXPECT_EQ(r.t, 5.0);
  EXPECT_EQ(r.clearance, 0.0);
  r = reference(ray({1.5f, 0, -5}, {0, 0, 1}), unit, 0);
  EXPECT_FALSE(r.hit);
  EXPECT_EQ(r.clearance, 1.25);  // |1 - 1.5^2|
  r = reference(ray({0, 0, 5}, {0, 0, 1}), unit, 0);  // behind the origin
  EXPECT_FALSE(r.hit);
  // 1e7 radii away: t = 1e7 - 1 exactly, which a float holds.
  r = reference(ray({0, 0, -1e7f}, {0, 0, 1}), unit, 0);
  EXPECT_TRUE(r.hit);
  EXPECT_EQ(r.t, 9999999.0);
  // Off center, far away: a line 0.5 from the center enters at t = 1e7 - sqrt(0.75).
  r = reference(ray({0.5f, 0, -1e7f}, {0, 0, 1}), unit, 0);
  EXPECT_NEAR(r.t, 1e7 - std::sqrt(0.75), 1e-8);
  EXPECT_EQ(r.clearance, 0.75);
}

TEST(AccuracyOracle, PlaneTriangleAndPolygonByHand) {
  BuildReport report;
  const PlaneSoA plane = build_planes(std::vector<PlaneDesc>{{{0, 0, 2}, {0, 0, 3}}}, report);
  Reference r = reference(ray({0, 0, 0}, {0, 0, 0.5f}), plane, 0);
  EXPECT_TRUE(r.hit);
  EXPECT_EQ(r.t, 4.0);
  EXPECT_EQ(r.clearance, 1.0);
  r = reference(ray({0, 0, 0}, {1, 0, 0}), plane, 0);  // parallel
  EXPECT_FALSE(r.hit);
  EXPECT_EQ(r.clearance, 0.0);

  const TriangleSoA tri = build_triangles(std::vector<TriangleDesc>{{{Vec3<float>{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {}, {}}}, report);
  r = reference(ray({0.25f, 0.25f, 1}, {0, 0, -1}), tri, 0);
  EXPECT_TRUE(r.hit);
  EXPECT_EQ(r.t, 1.0);
  EXPECT_EQ(r.clearance, 0.25);
  r = reference(ray({0.6f, 0.6f, 1}, {0, 0, -1}), tri, 0);
  EXPECT_FALSE(r.hit);
  EXPECT_NEAR(r.clearance, 0.2, 1e-7);  // the weight of v0 is 1 - 1.2 (float 0.6)
  r = reference(ray({0.5f, 0.5f, 1}, {0, 0, -2}), tri, 0);  // on the hypotenuse: inside
  EXPECT_TRUE(r.hit);
  EXPECT_EQ(r.t, 0.5);
  EXPECT_EQ(r.clearance, 0.0);

  // An L: the notch (1..2, 1..2) is outside.
  const PolygonSoA ell = build_polygons(
      std::vector<PolygonDesc>{{{{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}}}}, report);
  r = reference(ray({1.5f, 1.5f, 1}, {0, 0, -1}), ell, 0);
  EXPECT_FALSE(r.hit);
  EXPECT_EQ(r.clearance, 0.25);  // 0.5 from the notch's edges, extent 2
  r = reference(ray({0.5f, 1.5f, 1}, {0, 0, -1}), ell, 0);
  EXPECT_TRUE(r.hit);
  EXPECT_EQ(r.t, 1.0);
  EXPECT_EQ(r.clearance, 0.25);
}

TEST(AccuracyOracle, ConeAndCylinderByHand) {
  BuildReport report;
  const ConeSoA cones = build_cones(std::vector<ConeDesc>{{{0, 0, 0}, 1, {0, 0, 2}, 1},   // cylinder
                                                          {{0, 0, 0}, 1, {0, 0, 1}, 0}},  // cone to a tip
                                    report);
  ASSERT_EQ(cones.size(), 2u);
  Reference r = reference(ray({-5, 0, 1}, {1, 0, 0}), cones, 0);
  EXPECT_TRUE(r.hit);
  EXPECT_EQ(r.t, 4.0);
  EXPECT_EQ(r.clearance, 0.5);  // half way up: s / h = 0.5
  r = reference(ray({0, 0.5f, 5}, {0, 0, -1}), cones, 0);  // parallel to the axis, inside
  EXPECT_FALSE(r.hit);
  r = reference(ray({0, 0, 0.5f}, {1, 0, 0}), cones, 0);  // from the axis: the inner wall
  EXPECT_TRUE(r.hit);
  EXPECT_EQ(r.t, 1.0);
  r = reference(ray({-5, 0, 0.5f}, {1, 0, 0}), cones, 1);  // radius 0.5 at half height
  EXPECT_TRUE(r.hit);
  EXPECT_EQ(r.t, 4.5);
  r = reference(ray({-5, 0, 3}, {1, 0, 0}), cones, 0);  // above the slab
  EXPECT_FALSE(r.hit);
}

TEST(AccuracyOracle, ClosestOfSeveralTakesTheNearestAndTheSmallerIdOnTies) {
  BuildReport report;
  SphereSoA spheres = build_spheres(std::vector<SphereDesc>{{{0, 0, 10}, 1}, {{0, 0, 4}, 1}, {{0, 0, 4}, 1}}, report);
  spheres.id_base = 7;
  const Reference r = closest_reference(ray({0, 0, 0}, {0, 0, 1}), spheres);
  EXPECT_TRUE(r.hit);
  EXPECT_EQ(r.t, 3.0);
  EXPECT_EQ(r.id, 8);
}

// The double-lane evaluation really runs in double: on a sweep case where
// the float algebraic sphere is off by more than 1e-5, the same template in
// Lane64 is within 1e-9 (a silent float conversion would show float errors).
TEST(AccuracyDoubleLanes, KernelTemplatesEvaluateInDouble) {
  const Method& algebraic = find_method("sphere", "algebraic");
  const Case c = make_case(Kind::sphere, Distribution::distance, 1e4, 2000, 1);
  const std::vector<Reference> refs = run_oracle(c.rays, c.prims);
  const ErrorStats in_float = compare(refs, hits_of(run_unit(algebraic, KernelUnit::scalar, c.rays, c.prims)), false);
  const ErrorStats in_double = compare(refs, run_double(algebraic, c.rays, c.prims), false);
  std::printf("[ measured ] algebraic sphere at distance 1e4: relative t error %.3g in float, %.3g in double\n",
              in_float.relative_max, in_double.relative_max);
  EXPECT_GT(in_float.relative_max, 1e-5);
  EXPECT_LT(in_double.relative_max, 1e-9);
  EXPECT_GT(in_double.both_hit, 500u);
  // Every method's double evaluation agrees with the oracle on a plain case.
  for (const Method& m : kMethods) {
    const Case easy = make_case(m.kind, Distribution::distance, 10.0, 500, 3);
    const ErrorStats s = compare(run_oracle(easy.rays, easy.prims), run_double(m, easy.rays, easy.prims), false);
    EXPECT_EQ(s.false_miss + s.false_hit, 0u) << m.kind_name << "/" << m.name;
    EXPECT_LT(s.relative_max, 1e-6) << m.kind_name << "/" << m.name;
    EXPECT_GT(s.both_hit, 50u) << m.kind_name << "/" << m.name;
  }
}

// The stress cases are what they say: about half of the rays hit, and the
// grazing sphere rays pass within the stated distance of the silhouette.
TEST(AccuracyStress, CasesMixHitsAndMissesAndGrazingRaysGraze) {
  for (const Method& m : kMethods) {
    const Case c = make_case(m.kind, Distribution::distance, 10.0, 1000, 1);
    std::size_t hits = 0;
    for (const Reference& r : run_oracle(c.rays, c.prims)) hits += r.hit ? 1 : 0;
    EXPECT_GT(hits, 150u) << m.kind_name;
    EXPECT_LT(hits, 850u) << m.kind_name;
  }
  const Case grazing = make_case(Kind::sphere, Distribution::grazing, 1e-4, 1000, 1);
  for (const Reference& r : run_oracle(grazing.rays, grazing.prims)) {
    EXPECT_LT(r.clearance, 2.1e-4 + 1e-6);  // |1 - b^2| for b = 1 +- 1e-4, plus the float rounding of the ray
  }
}

}  // namespace
}  // namespace quiver::accuracy
