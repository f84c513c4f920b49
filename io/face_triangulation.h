// A mesh face's corner triples, shared by the OBJ and PLY readers: a fan
// for triangles and convex polygons (convex by the turn at every corner
// against the Newell normal, in double), ear clipping
// (triangulate_polygon, geometry/kinds/polygon.h) for concave ones, and a
// fan again when ear clipping declines (non-planar or degenerate faces; the
// triangle builder drops what is degenerate). At most n - 2 triples (fewer
// where ear clipping drops collinear corners), each of corner indices into p.
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "simd/vec3.h"

namespace quiver {

void triangulate_face(std::span<const Vec3<float>> p, std::vector<std::array<std::size_t, 3>>& triples);

}  // namespace quiver
