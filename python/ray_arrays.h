// Rays as NumPy hands them over: two C-contiguous (N, 3) arrays of float32
// or float64 (origins, directions; both of one type), read in batches into
// RaySoA with one (tmin, tmax) for every ray. float64 values are rounded to
// float32 (to nearest) as they are read, batch by batch, so no whole copy
// is made. A ray with a non-finite origin or direction (after rounding) or
// a zero direction is bad: it is read as an empty ray (tmin = tmax = 0,
// which no query can hit) and reported, the first one by index, after the
// query (first_bad_ray, bad_ray_message).
#pragma once

#include <atomic>
#include <cstddef>
#include <limits>
#include <string>

#include "geometry/soa.h"

namespace quiver {

// Rays per batch: as `quiver trace`'s 16x16 pixel tiles, so the batches of
// its rays (python camera_rays) are its tiles.
inline constexpr std::size_t kRayBatchSize = 256;

enum class ArrayFloat { float32, float64 };

struct RayArrays {
  const void* origins = nullptr;     // count x 3, row-major
  const void* directions = nullptr;  // count x 3, row-major
  std::size_t count = 0;
  ArrayFloat type = ArrayFloat::float32;
};

// The ray interval every query uses: tmin finite and >= 0, tmax > tmin (inf allowed).
struct RayInterval {
  float tmin = 0.f;
  float tmax = std::numeric_limits<float>::infinity();
};

// Throws std::invalid_argument unless tmin is finite and >= 0 and tmax
// (after rounding to float32) is greater than tmin; names the arguments as
// the Python functions do.
RayInterval checked_interval(double tmin, double tmax);

std::size_t batch_count(std::size_t rays);

// Reads batch b (rays [b * kRayBatchSize, ...)) into rays (all of it
// replaced, padded); lowers first_bad to the index of the batch's first bad
// ray.
void read_ray_batch(const RayArrays& arrays, std::size_t b, const RayInterval& interval, RaySoA& rays,
                    std::atomic<std::size_t>& first_bad);

// "origins[i] = (x, y, z) is not finite in float32" or the like for ray i.
std::string bad_ray_message(const RayArrays& arrays, std::size_t i);

}  // namespace quiver
