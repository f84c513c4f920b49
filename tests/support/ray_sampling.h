// Deterministic ray generators for tests and benchmarks: random, aimed, and adversarial.
#pragma once

#include <cstdint>
#include <random>
#include <span>
#include <vector>

#include "geometry/soa.h"

namespace quiver::testing {

class RaySampler {
 public:
  explicit RaySampler(std::uint32_t seed) : rng_(seed) {}
  float uniform(float lo, float hi);
  int uniform_int(int lo, int hi);  // inclusive
  Vec3<float> in_box(const Vec3<float>& lo, const Vec3<float>& hi);
  Vec3<float> unit_direction();  // uniform on the sphere
  // A ray from origin through target, direction not normalised, (0, inf).
  Ray<float> toward(const Vec3<float>& origin, const Vec3<float>& target);

 private:
  std::mt19937 rng_;
};

// Rays that break naive code: NaN/Inf origins and directions, zero
// directions, empty or inverted (tmin, tmax), huge and tiny magnitudes, and
// ordinary rays toward the ball (center, radius) in between.
std::vector<Ray<float>> adversarial_rays(RaySampler& sampler, std::size_t count,
                                         const Vec3<float>& center, float radius);

RaySoA to_soa(std::span<const Ray<float>> rays);
// Writes NaN and Inf into the padding lanes past rays.count: they are
// inactive and must not change any active lane's result.
void poison_padding(RaySoA& rays);

}  // namespace quiver::testing
