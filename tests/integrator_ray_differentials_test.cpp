// Ray differentials (integrator/ray_differentials.h) against central
// differences of the functions they differentiate: the hit point on a plane,
// and the reflected and refracted directions as the incident direction and
// the normal turn.
#include <cmath>

#include <gtest/gtest.h>

#include "integrator/optics.h"
#include "integrator/ray_differentials.h"

namespace quiver {
namespace {

using V = Vec3<double>;

Vec3<float> to_float(const V& v) { return {float(v.x), float(v.y), float(v.z)}; }
V to_double(const Vec3<float>& v) { return {v.x, v.y, v.z}; }
V unit(const V& v) { return v / std::sqrt(dot(v, v)); }

void expect_near(const Vec3<float>& got, const V& want, double tolerance) {
  EXPECT_NEAR(got.x, want.x, tolerance);
  EXPECT_NEAR(got.y, want.y, tolerance);
  EXPECT_NEAR(got.z, want.z, tolerance);
}

// Central difference of f(s) at 0.
template <class Function>
V derivative(Function f) {
  const double h = 1e-3;
  return (to_double(f(h)) - to_double(f(-h))) / (2.0 * h);
}

TEST(RayDifferentials, TransferFollowsTheHitPointAcrossAPlane) {
  const V plane_point{0.3, -1.0, 0.2}, normal = unit({0.2, 1.0, -0.3});
  const V origin{0.0, 2.0, 1.0}, direction = unit({0.3, -1.0, -0.4});
  const V d_origin{0.01, 0.0, -0.02}, d_direction{0.02, 0.01, 0.03};
  auto hit = [&](double s) {
    const V o = origin + d_origin * s, d = direction + d_direction * s;
    const double t = dot(plane_point - o, normal) / dot(d, normal);
    return to_float(o + d * t);
  };
  const double t = dot(plane_point - origin, normal) / dot(direction, normal);
  const Vec3<float> dp = transfer_differential<float>(to_float(d_origin), to_float(d_direction), to_float(direction),
                                                      float(t), to_float(normal * 3.0));  // any length of normal
  expect_near(dp, derivative(hit), 2e-4);
  EXPECT_NEAR(dot(to_double(dp), normal), 0.0, 1e-6);  // it stays in the plane
}

TEST(RayDifferentials, ReflectionAndRefractionTurnWithTheIncidentRayAndTheNormal) {
  const V incident = unit({0.4, -1.0, 0.2}), normal = unit({0.1, 1.0, 0.05});
  // Changes perpendicular to each unit vector, so both stay unit to first order.
  const V d_incident = V{0.05, 0.0, -0.1} - incident * dot(V{0.05, 0.0, -0.1}, incident);
  const V d_normal = V{0.02, 0.0, 0.07} - normal * dot(V{0.02, 0.0, 0.07}, normal);
  auto turned = [&](double s) {
    return std::pair{to_float(unit(incident + d_incident * s)), to_float(unit(normal + d_normal * s))};
  };
  const Vec3<float> i = to_float(incident), n = to_float(normal), di = to_float(d_incident), dn = to_float(d_normal);

  const V want_reflected = derivative([&](double s) {
    const auto [is, ns] = turned(s);
    return reflect<float>(is, ns);
  });
  expect_near(reflect_differential<float>(i, di, n, dn), want_reflected, 2e-4);

  for (float eta : {1.f / 1.5f, 1.2f}) {
    SCOPED_TRACE(eta);
    bool transmitted = false;
    const Vec3<float> refracted = refract<float>(i, n, eta, transmitted);
    ASSERT_TRUE(transmitted);
    const V want_refracted = derivative([&](double s) {
      const auto [is, ns] = turned(s);
      bool through = false;
      return refract<float>(is, ns, eta, through);
    });
    expect_near(refract_differential<float>(i, di, n, dn, eta, refracted), want_refracted, 5e-4);
  }
}

}  // namespace
}  // namespace quiver
