#include "python/ray_arrays.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace quiver {

namespace {

template <class T>
Vec3<float> row(const void* array, std::size_t i) {
  const T* p = static_cast<const T*>(array) + 3 * i;
  return {static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])};
}

Vec3<float> row(const void* array, ArrayFloat type, std::size_t i) {
  return type == ArrayFloat::float32 ? row<float>(array, i) : row<double>(array, i);
}

// 1 for a ray the queries cannot use, else 0: a coordinate not finite (its
// exponent bits all ones) or a zero direction (no bit besides the signs
// set). Integer tests with no branch, so the pass over a batch vectorizes.
inline std::uint32_t unusable(float ox, float oy, float oz, float dx, float dy, float dz) {
  constexpr std::uint32_t exponent = 0x7f800000u, magnitude = 0x7fffffffu;
  const auto bits = [](float x) { return std::bit_cast<std::uint32_t>(x); };
  const auto not_finite = [&](float x) { return std::uint32_t((bits(x) & exponent) == exponent); };
  return not_finite(ox) | not_finite(oy) | not_finite(oz) | not_finite(dx) | not_finite(dy) | not_finite(dz) |
         std::uint32_t(((bits(dx) | bits(dy) | bits(dz)) & magnitude) == 0);
}

// Writes the columns by index, then checks the batch in one pass over them
// (push per ray costs a call and eight capacity checks, a check per ray a
// branch; this is a fair part of intersect's time).
template <class T>
void read_batch(const RayArrays& arrays, std::size_t first, std::size_t last, const RayInterval& interval,
                RaySoA& rays, std::atomic<std::size_t>& first_bad) {
  const std::size_t n = last - first;
  rays.count = n;
  for (AlignedFloats* column : {&rays.ox, &rays.oy, &rays.oz, &rays.dx, &rays.dy, &rays.dz}) column->resize(n);
  rays.tmin.assign(n, interval.tmin);
  rays.tmax.assign(n, interval.tmax);
  const T* o = static_cast<const T*>(arrays.origins) + 3 * first;
  const T* d = static_cast<const T*>(arrays.directions) + 3 * first;
  float *ox = rays.ox.data(), *oy = rays.oy.data(), *oz = rays.oz.data();
  float *dx = rays.dx.data(), *dy = rays.dy.data(), *dz = rays.dz.data();
  for (std::size_t i = 0; i < n; ++i) {
    ox[i] = static_cast<float>(o[3 * i]);
    oy[i] = static_cast<float>(o[3 * i + 1]);
    oz[i] = static_cast<float>(o[3 * i + 2]);
    dx[i] = static_cast<float>(d[3 * i]);
    dy[i] = static_cast<float>(d[3 * i + 1]);
    dz[i] = static_cast<float>(d[3 * i + 2]);
  }
  std::uint32_t any_unusable = 0;
  for (std::size_t i = 0; i < n; ++i) any_unusable |= unusable(ox[i], oy[i], oz[i], dx[i], dy[i], dz[i]);
  if (any_unusable != 0) {
    std::size_t bad = n;
    for (std::size_t i = 0; i < n; ++i) {
      if (unusable(ox[i], oy[i], oz[i], dx[i], dy[i], dz[i]) == 0) continue;
      bad = std::min(bad, i);
      rays.set(i, {{0.f, 0.f, 0.f}, {1.f, 0.f, 0.f}, 0.f, 0.f});
    }
    std::size_t seen = first_bad.load(std::memory_order_relaxed);
    while (first + bad < seen && !first_bad.compare_exchange_weak(seen, first + bad, std::memory_order_relaxed)) {
    }
  }
  rays.pad();
}

std::string vector_text(const Vec3<float>& v) {
  std::ostringstream text;
  text.precision(9);
  text << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return text.str();
}

}  // namespace

RayInterval checked_interval(double tmin, double tmax) {
  if (!(std::isfinite(tmin) && tmin >= 0.0)) {
    throw std::invalid_argument("tmin: expected a finite number >= 0, found " + std::to_string(tmin));
  }
  const RayInterval interval{static_cast<float>(tmin), static_cast<float>(tmax)};
  if (!std::isfinite(interval.tmin) || !(interval.tmax > interval.tmin)) {
    throw std::invalid_argument("tmax: expected a number greater than tmin (" + std::to_string(tmin) +
                                ") in float32, found " + std::to_string(tmax));
  }
  return interval;
}

std::size_t batch_count(std::size_t rays) { return (rays + kRayBatchSize - 1) / kRayBatchSize; }

void read_ray_batch(const RayArrays& arrays, std::size_t b, const RayInterval& interval, RaySoA& rays,
                    std::atomic<std::size_t>& first_bad) {
  const std::size_t first = b * kRayBatchSize, last = std::min(arrays.count, first + kRayBatchSize);
  if (arrays.type == ArrayFloat::float32) {
    read_batch<float>(arrays, first, last, interval, rays, first_bad);
  } else {
    read_batch<double>(arrays, first, last, interval, rays, first_bad);
  }
}

std::string bad_ray_message(const RayArrays& arrays, std::size_t i) {
  const Vec3<float> o = row(arrays.origins, arrays.type, i), d = row(arrays.directions, arrays.type, i);
  std::ostringstream message;
  if (!all_finite(o)) {
    message << "origins[" << i << "] = " << vector_text(o) << " is not finite in float32";
  } else if (!all_finite(d)) {
    message << "directions[" << i << "] = " << vector_text(d) << " is not finite in float32";
  } else {
    message << "directions[" << i << "] is (0, 0, 0): a ray needs a direction";
  }
  return message.str();
}

}  // namespace quiver
