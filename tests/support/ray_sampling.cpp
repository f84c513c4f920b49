#include "tests/support/ray_sampling.h"

#include <cmath>
#include <limits>

namespace quiver::testing {

float RaySampler::uniform(float lo, float hi) {
  return std::uniform_real_distribution<float>(lo, hi)(rng_);
}

int RaySampler::uniform_int(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }

Vec3<float> RaySampler::in_box(const Vec3<float>& lo, const Vec3<float>& hi) {
  return {uniform(lo.x, hi.x), uniform(lo.y, hi.y), uniform(lo.z, hi.z)};
}

Vec3<float> RaySampler::unit_direction() {
  const float z = uniform(-1.f, 1.f);
  const float phi = uniform(0.f, 6.2831853f);
  const float r = std::sqrt(std::max(0.f, 1.f - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

Ray<float> RaySampler::toward(const Vec3<float>& origin, const Vec3<float>& target) {
  return {origin, target - origin, 0.f, std::numeric_limits<float>::infinity()};
}

std::vector<Ray<float>> adversarial_rays(RaySampler& s, std::size_t count, const Vec3<float>& center,
                                         float radius) {
  constexpr float inf = std::numeric_limits<float>::infinity();
  constexpr float nan = std::numeric_limits<float>::quiet_NaN();
  const float specials[] = {nan, inf, -inf, 0.f, -0.f, 1e30f, -1e30f, 1e-30f, 1e-40f /* denormal */};
  std::vector<Ray<float>> rays;
  rays.reserve(count);
  const Vec3<float> reach{radius * 3, radius * 3, radius * 3};
  for (std::size_t i = 0; i < count; ++i) {
    Ray<float> r = s.toward(s.in_box(center - reach, center + reach),
                            s.in_box(center - Vec3<float>{radius, radius, radius},
                                     center + Vec3<float>{radius, radius, radius}));
    switch (i % 8) {
      case 0: r.origin[s.uniform_int(0, 2)] = specials[s.uniform_int(0, 8)]; break;
      case 1: r.direction[s.uniform_int(0, 2)] = specials[s.uniform_int(0, 8)]; break;
      case 2: r.direction = {0.f, 0.f, 0.f}; break;
      case 3: std::swap(r.tmin, r.tmax); break;  // empty interval
      case 4: r.tmin = specials[s.uniform_int(0, 8)]; break;
      case 5: r.tmax = specials[s.uniform_int(0, 8)]; break;
      case 6: r.direction = r.direction * 1e-20f; break;  // tiny direction, huge t
      default: break;  // an ordinary ray among the hostile ones
    }
    rays.push_back(r);
  }
  return rays;
}

RaySoA to_soa(std::span<const Ray<float>> rays) {
  RaySoA soa(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) soa.set(i, rays[i]);
  soa.pad();
  return soa;
}

void poison_padding(RaySoA& rays) {
  constexpr float nan = std::numeric_limits<float>::quiet_NaN();
  constexpr float inf = std::numeric_limits<float>::infinity();
  for (std::size_t i = rays.count; i < rays.ox.size(); ++i) {
    const float bad = (i % 2) ? nan : inf;
    for (AlignedFloats* c : {&rays.ox, &rays.oy, &rays.oz, &rays.dx, &rays.dy, &rays.dz}) (*c)[i] = bad;
    rays.tmin[i] = -inf;
    rays.tmax[i] = inf;
  }
}

}  // namespace quiver::testing
