// Ray<F>: origin, direction (not necessarily unit length) and the open
// parameter interval (tmin, tmax) in which hits count.
#pragma once

#include <limits>

#include "simd/lanes.h"

namespace quiver {

template <class F>
struct Ray {
  Vec3<F> origin;
  Vec3<F> direction;
  F tmin;
  F tmax;
};

inline namespace QUIVER_UNIT_NAMESPACE {

// One ray copied into every lane.
template <class F>
inline Ray<F> broadcast_ray(const Ray<float>& r) {
  if constexpr (lane_count<F> == 1) {
    return r;
  } else {
    return {Vec3<F>(r.origin), Vec3<F>(r.direction), F(r.tmin), F(r.tmax)};
  }
}

// Base of kernel methods that need no per-ray setup: prepare() is the ray.
struct RayAsIs {
  template <class F>
  static const Ray<F>& prepare(const Ray<F>& ray) {
    return ray;
  }
};

}  // namespace QUIVER_UNIT_NAMESPACE
}  // namespace quiver
