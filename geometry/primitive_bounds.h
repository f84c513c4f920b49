// Conservative axis-aligned boxes of stored primitives: each kind's
// primitive_box (geometry/kinds/<kind>.h) bounds the surface the kernels
// intersect, as stored, computed in double and rounded outward to float.
// Infinite planes have no box.
#pragma once

#include <cstddef>

#include "geometry/box.h"

namespace quiver {

// Grows b by the points c +- r per axis (c and r in double), rounded outward.
void grow_ball(Box& b, const double c[3], double r);

// The box of primitives [0, store.count) (empty for none).
template <class Store>
Box store_box(const Store& store) {
  Box bounds = empty_box();
  for (std::size_t i = 0; i < store.count; ++i) grow(bounds, primitive_box(store, i));
  return bounds;
}

}  // namespace quiver
