// Structure-of-arrays storage shared by every primitive kind and by ray and
// hit streams: 64-byte aligned columns padded to a multiple of kMaxLanes, so
// any width loads whole lanes. Padding lanes hold copies of the last real
// element (valid numbers, no NaN) and are always masked off.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/hit.h"
#include "simd/lanes.h"
#include "simd/ray.h"

namespace quiver {

using AlignedFloats = std::vector<float, xsimd::aligned_allocator<float, 64>>;
using AlignedInts = std::vector<std::int32_t, xsimd::aligned_allocator<std::int32_t, 64>>;

// Room for a full load from any index below n (BVH leaves start anywhere),
// rounded to whole kMaxLanes blocks.
constexpr std::size_t padded_size(std::size_t n) {
  return n == 0 ? 0 : (n + 2 * kMaxLanes - 2) / kMaxLanes * kMaxLanes;
}

// Bytes a vector holds (its capacity), for memory reports.
template <class Vec>
std::size_t bytes_of(const Vec& v) {
  return v.capacity() * sizeof(typename Vec::value_type);
}

// Sizes the column to padded_size(count) and fills [count, padded) with
// column[count - 1] (zeros when count is 0).
void pad_column(AlignedFloats& column, std::size_t count);
void pad_column(AlignedInts& column, std::size_t count);

inline namespace QUIVER_UNIT_NAMESPACE {

template <class F>
inline Vec3<F> load_vec3(const AlignedFloats& x, const AlignedFloats& y, const AlignedFloats& z,
                         std::size_t first) {
  return {load_lanes<F>(x.data() + first), load_lanes<F>(y.data() + first),
          load_lanes<F>(z.data() + first)};
}
// A primitive store's lanes [first, first + W), first any index (BVH leaves).
template <class F>
inline Vec3<F> load_vec3_unaligned(const AlignedFloats& x, const AlignedFloats& y, const AlignedFloats& z,
                                   std::size_t first) {
  return {load_lanes_unaligned<F>(x.data() + first), load_lanes_unaligned<F>(y.data() + first),
          load_lanes_unaligned<F>(z.data() + first)};
}
template <class F>
inline Vec3<F> broadcast_vec3(const AlignedFloats& x, const AlignedFloats& y,
                              const AlignedFloats& z, std::size_t i) {
  return {F(x[i]), F(y[i]), F(z[i])};
}

}  // namespace QUIVER_UNIT_NAMESPACE

// Rays in SoA; a closest-hit stream reads (tmin, tmax) from here.
struct RaySoA {
  AlignedFloats ox, oy, oz, dx, dy, dz, tmin, tmax;
  std::size_t count = 0;

  RaySoA() = default;
  explicit RaySoA(std::size_t n);
  void set(std::size_t i, const Ray<float>& ray);
  Ray<float> get(std::size_t i) const;
  // Building a stream in place, keeping capacity: clear(), push()..., pad(),
  // or resize(n), set() of rays [0, n), pad().
  void clear();
  void push(const Ray<float>& ray);
  void resize(std::size_t n);
  // Call after the last set(): copies the last ray into the padding lanes.
  void pad();
  // Every column, the one list of them.
  std::array<AlignedFloats*, 8> columns() { return {&ox, &oy, &oz, &dx, &dy, &dz, &tmin, &tmax}; }

  template <class F>
  [[gnu::always_inline]] Ray<F> load(std::size_t first) const {
    return {load_vec3<F>(ox, oy, oz, first), load_vec3<F>(dx, dy, dz, first),
            load_lanes<F>(tmin.data() + first), load_lanes<F>(tmax.data() + first)};
  }
};

// Closest hits in SoA. t holds the current closest distance and is read as
// each ray's tmax, so streams over several primitive kinds compose.
struct HitSoA {
  AlignedFloats t, u, v, ngx, ngy, ngz;
  AlignedInts id;
  std::size_t count = 0;

  HitSoA() = default;
  // t = ray tmax, id = kNoHit for every ray.
  explicit HitSoA(const RaySoA& rays);
  // As the constructor, keeping capacity.
  void reset(const RaySoA& rays);
  Hit<float> get(std::size_t i) const;
  void set(std::size_t i, const Hit<float>& hit);
  std::size_t hit_count() const;  // rays with id != kNoHit

  template <class F>
  [[gnu::always_inline]] Hit<F> load(std::size_t first) const {
    return load_column_hits<F>(*this, first);
  }
  template <class F>
  [[gnu::always_inline]] void store(std::size_t first, const Hit<F>& hit) {
    store_column_hits(*this, first, hit);
  }
};

// Any-hit results: occluded[i] is 1 once ray i is blocked within (tmin, tmax).
struct OcclusionSoA {
  AlignedInts occluded;
  std::size_t count = 0;

  OcclusionSoA() = default;
  explicit OcclusionSoA(const RaySoA& rays);
  // As the constructor, keeping capacity.
  void reset(const RaySoA& rays);
};

}  // namespace quiver
