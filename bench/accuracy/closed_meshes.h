// Closed meshes for the watertightness study: every edge is shared by
// exactly two faces with opposite directions. Built in double, rounded to
// float once, so shared vertices are bit-identical in both faces.
//   octasphere(levels): the octahedron, each triangle split in four per level,
//                       new vertices pushed onto the unit sphere (8 * 4^levels faces);
//   box_triangles:      an axis-aligned box, two triangles per side;
//   box_quads:          the same box as six quadrilateral polygons;
//   prism:              a 2D outline extruded: its top and bottom as two
//                       polygons of the outline's vertices, its sides as quads.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <random>
#include <utility>
#include <vector>

#include "geometry/kinds/polygon.h"
#include "geometry/kinds/triangle.h"
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

// A simple 2D outline, counter-clockwise (convex or concave).
using Outline = std::vector<std::array<double, 2>>;
Outline regular_outline(int sides, double radius);                // convex
Outline star_outline(int points, double inner, double outer);     // 2 vertices a point
Outline gear_outline(int teeth, double root, double tip);         // 4 vertices a tooth

// The outline extruded over z0 < z < z1, then moved by `offset`, and the
// origins of rays from strictly inside it (checked in double on the float
// origin): a third anywhere, a third within `nearest`..1e-2 of the height
// from the top or the bottom, a third within `nearest`..1e-3 of a side's
// length from a side (log-uniform; just `nearest` when it is larger), so
// rays aimed at the edges include grazing ones; none nearer to the caps
// than `nearest` of the height, or to the sides than `nearest` of the
// shortest side. (Within a few float spacings of the coordinates from a
// face, the sign of the plane hit's t, which the polygon test keeps, is a
// coin toss.)
struct Prism {
  ClosedMesh mesh;
  Outline outline;
  double z0, z1;
  Vec3<double> offset;
};
Prism prism(const Outline& outline, double z0, double z1, const Vec3<double>& offset);

// Ray origins strictly inside a closed mesh, one a call.
using OriginSampler = std::function<Vec3<float>(std::mt19937_64&)>;
OriginSampler prism_interior(const Prism& prism, double nearest = 1e-5);

}  // namespace quiver::accuracy
