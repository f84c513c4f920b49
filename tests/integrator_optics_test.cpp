// Reflection and Snell refraction against hand-computed directions, total
// internal reflection, and the ray-origin offset.
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

#include <gtest/gtest.h>

#include "integrator/optics.h"

namespace quiver {
namespace {

void expect_near(const Vec3<float>& a, double x, double y, double z, double tol = 1e-6) {
  EXPECT_NEAR(a.x, x, tol);
  EXPECT_NEAR(a.y, y, tol);
  EXPECT_NEAR(a.z, z, tol);
}

TEST(Optics, ReflectionMirrorsTheNormalComponent) {
  const float s = float(std::sqrt(0.5));
  expect_near(reflect<float>({s, -s, 0.f}, {0.f, 1.f, 0.f}), s, s, 0.0);
  expect_near(reflect<float>({0.f, 0.f, -1.f}, {0.f, 0.f, 1.f}), 0.0, 0.0, 1.0);
}

TEST(Optics, SnellIntoGlassAt45Degrees) {
  // sin(theta2) = sin(45) / 1.5 = 0.4714045; cos(theta2) = 0.8819171.
  const float s = float(std::sqrt(0.5));
  bool transmitted = false;
  const Vec3<float> t = refract<float>({s, -s, 0.f}, {0.f, 1.f, 0.f}, 1.f / 1.5f, transmitted);
  ASSERT_TRUE(transmitted);
  const double sin2 = std::sqrt(0.5) / 1.5;
  expect_near(t, sin2, -std::sqrt(1.0 - sin2 * sin2), 0.0);
  EXPECT_NEAR(dot(t, t), 1.f, 1e-6f);  // unit in, unit out
}

TEST(Optics, NormalIncidencePassesStraight) {
  bool transmitted = false;
  const Vec3<float> t = refract<float>({0.f, 0.f, -1.f}, {0.f, 0.f, 1.f}, 1.f / 1.33f, transmitted);
  ASSERT_TRUE(transmitted);
  expect_near(t, 0.0, 0.0, -1.0);
}

TEST(Optics, TotalInternalReflectionBeyondTheCriticalAngle) {
  // Glass to air: critical angle asin(1 / 1.5) = 41.81 degrees.
  const double critical = std::asin(1.0 / 1.5);
  for (double degrees : {42.0, 60.0, 89.9}) {
    const double a = degrees * M_PI / 180.0;
    bool transmitted = true;
    const Vec3<float> t = refract<float>({float(std::sin(a)), float(-std::cos(a)), 0.f}, {0.f, 1.f, 0.f}, 1.5f, transmitted);
    EXPECT_FALSE(transmitted) << degrees;
    EXPECT_FALSE(std::isnan(t.x) || std::isnan(t.y) || std::isnan(t.z)) << degrees;  // masked garbage, never NaN
  }
  const double below = critical - 1e-3;
  bool transmitted = false;
  const Vec3<float> t = refract<float>({float(std::sin(below)), float(-std::cos(below)), 0.f}, {0.f, 1.f, 0.f}, 1.5f,
                                  transmitted);
  ASSERT_TRUE(transmitted);
  EXPECT_GT(t.x, 0.99f);  // grazing out along the surface
  EXPECT_FALSE(std::isnan(t.y));
}

// Fresnel reflectance against the textbook values: ((n - 1) / (n + 1))^2 =
// 0.04 at normal incidence into or out of glass, 1 at grazing incidence
// and beyond the critical angle, 0 between equal media, and at 45 degrees
// into glass the mean of rs^2 and rp^2 from Snell's angle in double.
TEST(Optics, FresnelReflectanceOfADielectric) {
  const Vec3<float> normal{0.f, 1.f, 0.f}, down{0.f, -1.f, 0.f};
  EXPECT_NEAR(fresnel_reflectance<float>(down, normal, 1.f / 1.5f), 0.04, 1e-6);
  EXPECT_NEAR(fresnel_reflectance<float>(down, normal, 1.5f), 0.04, 1e-6);
  EXPECT_EQ(fresnel_reflectance<float>(down, normal, 1.f), 0.f);
  EXPECT_NEAR(fresnel_reflectance<float>({1.f, -1e-4f, 0.f}, normal, 1.f / 1.5f), 1.0, 1e-3);
  const float s = float(std::sqrt(0.5));
  EXPECT_EQ(fresnel_reflectance<float>({s, -s, 0.f}, normal, 1.5f), 1.f);  // past asin(1 / 1.5)
  const double ci = std::sqrt(0.5), st = std::sqrt(0.5) / 1.5, ct = std::sqrt(1.0 - st * st);
  const double rs = (ci - 1.5 * ct) / (ci + 1.5 * ct), rp = (1.5 * ci - ct) / (1.5 * ci + ct);
  EXPECT_NEAR(fresnel_reflectance<float>({s, -s, 0.f}, normal, 1.f / 1.5f), 0.5 * (rs * rs + rp * rp), 1e-6);
}

// The lift's share: whole where the face turns from the light, none where
// N.L and Ng.L both reach the band, linear between, and continuous where
// N.L crosses the band.
TEST(Optics, TerminatorLiftShareFadesOutOverTheBand) {
  const float band = kTerminatorBand;
  EXPECT_EQ(terminator_lift_share(0.5f, -0.2f), 1.f);
  EXPECT_EQ(terminator_lift_share(0.5f, 0.f), 1.f);
  EXPECT_EQ(terminator_lift_share(band, band), 0.f);
  EXPECT_EQ(terminator_lift_share(0.9f, 0.8f), 0.f);
  EXPECT_NEAR(terminator_lift_share(0.05f, 0.12f), 2.0 - 0.17 / 0.1, 1e-5);  // N.L in the band
  EXPECT_NEAR(terminator_lift_share(0.5f, 0.03f), 1.0 - 0.03 / 0.1, 1e-5);   // N.L above it
  EXPECT_NEAR(terminator_lift_share(std::nextafter(band, 0.f), 0.04f), terminator_lift_share(band, 0.04f), 1e-5);
}

TEST(Optics, OffsetMovesClearOfTheErrorOnTheChosenSide) {
  for (float scale : {1e-4f, 1.f, 1e6f}) {
    const Vec3<float> o{0.f, 10.f * scale, 0.f}, d{0.3f, -1.f, 0.2f};
    const float t = 10.f * scale;
    const Vec3<float> p = o + d * t;  // on the plane y = 0 up to rounding
    const Vec3<float> err = hit_point_error(o, d, t);
    EXPECT_GT(offset_origin(p, err, {0.f, 1.f, 0.f}).y, 0.f) << scale;
    EXPECT_LT(offset_origin(p, err, {0.f, -1.f, 0.f}).y, 0.f) << scale;
    // Clear of the surface by at least the bound, not by a scene epsilon.
    EXPECT_GE(offset_origin(p, err, {0.f, 1.f, 0.f}).y, err.y) << scale;
    EXPECT_LT(offset_origin(p, err, {0.f, 1.f, 0.f}).y, 1e-3f * scale) << scale;
  }
}

// The error bound grows with the distance travelled (|t d|) on every axis,
// not only with |o|: from the origin (|o| = 0) to an axis-aligned plane at
// a = s, the hit p = o + t d (float, as hit_position computes it) can land
// an ulp or two past the plane, and the offset back toward the origin must
// clear the plane at every scale s and for every direction reaching it.
TEST(Optics, OffsetClearsAPlaneReachedFromTheOriginOnEachAxis) {
  const Vec3<float> o{0.f, 0.f, 0.f};
  constexpr int kDirections = 512;
  const double golden_angle = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    Vec3<float> toward_origin{0.f, 0.f, 0.f};
    toward_origin[axis] = -1.f;
    int crossed = 0;
    for (float s : {1e-3f, 1.f, 1e3f, 1e6f}) {
      for (int i = 0; i < kDirections; ++i) {
        // Unit directions with d[axis] spread over [0.3, 1], turning about the axis.
        const double along = 0.3 + 0.7 * (i + 0.5) / kDirections;
        const double across = std::sqrt(1.0 - along * along), phi = golden_angle * i;
        Vec3<float> d{0.f, 0.f, 0.f};
        d[axis] = float(along);
        d[u] = float(across * std::cos(phi));
        d[v] = float(across * std::sin(phi));
        const float t = s / d[axis];
        const Vec3<float> p = o + d * t;
        if (p[axis] > s) ++crossed;
        const Vec3<float> moved = offset_origin(p, hit_point_error(o, d, t), toward_origin);
        EXPECT_LT(moved[axis], s) << "axis " << axis << " plane " << s << " direction " << i;
      }
    }
    // Some hits overshoot their plane in float (not at s = 1, a power of two,
    // where d (1 / d) never rounds above 1), so the bound is what clears them.
    EXPECT_GT(crossed, 0) << "axis " << axis;
  }
}

TEST(Optics, NextFloatAwayIsNextafterTowardTheSign) {
  const float inf = std::numeric_limits<float>::infinity();
  for (float x : {0.f, -0.f, 1.f, -1.f, 1e-38f, -3e38f, std::numeric_limits<float>::max(), inf, -inf}) {
    EXPECT_EQ(std::bit_cast<std::uint32_t>(next_float_away(x, 1.f)),
              std::bit_cast<std::uint32_t>(std::nextafter(x, inf))) << x;
    EXPECT_EQ(std::bit_cast<std::uint32_t>(next_float_away(x, -0.5f)),
              std::bit_cast<std::uint32_t>(std::nextafter(x, -inf))) << x;
    EXPECT_EQ(std::bit_cast<std::uint32_t>(next_float_away(x, 0.f)), std::bit_cast<std::uint32_t>(x)) << x;
  }
}

}  // namespace
}  // namespace quiver
