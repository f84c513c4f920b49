// Conservative axis-aligned boxes of stored primitives, one function per
// kind: the surface the kernels intersect, as stored (a sphere's r^2, a
// polygon's projected vertices on its stored plane, a cone's rims), computed
// in double and rounded outward to float. Triangle vertices are exact.
// Infinite planes have no box.
#pragma once

#include <cstddef>
#include <vector>

#include "geometry/bvh.h"
#include "geometry/cone_soa.h"
#include "geometry/polygon_soa.h"
#include "geometry/sphere_soa.h"
#include "geometry/triangle_soa.h"

namespace quiver {

Box primitive_box(const SphereSoA& spheres, std::size_t i);
Box primitive_box(const TriangleSoA& triangles, std::size_t i);
Box primitive_box(const PolygonSoA& polygons, std::size_t i);
Box primitive_box(const ConeSoA& cones, std::size_t i);

// The boxes of primitives [0, store.count).
template <class Store>
std::vector<Box> primitive_boxes(const Store& store) {
  std::vector<Box> boxes;
  boxes.reserve(store.count);
  for (std::size_t i = 0; i < store.count; ++i) boxes.push_back(primitive_box(store, i));
  return boxes;
}

}  // namespace quiver
