// Closed meshes for the watertightness study: every edge is shared by
// exactly two faces with opposite directions. Built in double, rounded to
// float once, so shared vertices are bit-identical in both faces.
//   octasphere(levels): the octahedron, each triangle split in four per level,
//                       new vertices pushed onto the unit sphere (8 * 4^levels faces);
//   box_triangles:      an axis-aligned box, two triangles per side;
//   box_quads:          the same box as six quadrilateral polygons.
#pragma once

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "geometry/polygon_soa.h"
#include "geometry/triangle_soa.h"
#include "simd/vec3.h"

namespace quiver::accuracy {

struct ClosedMesh {
  std::vector<Vec3<float>> positions;
  std::vector<std::vector<std::uint32_t>> faces;  // counter-clockwise seen from outside

  // Each undirected edge once (smaller index first).
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges() const;
  // Every directed edge appears once and its reverse once.
  bool closed() const;
  std::vector<TriangleDesc> triangles() const;  // faces must be triangles
  std::vector<PolygonDesc> polygons() const;
};

// Octasphere scaled per axis by `scale` and moved to `center`; each vertex
// first pushed radially by a factor in [1 - jitter, 1 + jitter] (seeded).
ClosedMesh octasphere(int levels, const Vec3<double>& center, const Vec3<double>& scale, double jitter,
                      std::uint32_t seed);
ClosedMesh box_triangles(const Vec3<double>& lo, const Vec3<double>& hi);
ClosedMesh box_quads(const Vec3<double>& lo, const Vec3<double>& hi);

}  // namespace quiver::accuracy
