// The primitives as a scene describes them, before their SoA stores are
// built (the builders in geometry/*_soa.h check and drop what is not
// finite or is degenerate). Plain structs: no lanes, no xsimd.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

#include "simd/vec3.h"

namespace quiver {

struct SphereDesc {
  Vec3<float> center;
  float radius;
};

// A plane through `point` with normal `normal` (any non-zero length).
struct PlaneDesc {
  Vec3<float> point;
  Vec3<float> normal;
};

struct TriangleDesc {
  std::array<Vec3<float>, 3> p;
  std::optional<std::array<Vec3<float>, 3>> normals;         // per vertex, any length
  std::optional<std::array<std::array<float, 2>, 3>> uvs;    // per vertex (u, v)
};

// Vertices in order (either winding; ng follows it counter-clockwise).
struct PolygonDesc {
  std::vector<Vec3<float>> vertices;
};
// Largest vertex count build_polygons accepts per polygon (more: degenerate).
inline constexpr std::size_t kMaxPolygonVertices = 1'000'000;

// NFF `c`: an open cone (a cylinder when the radii are equal) from the base
// circle (center, radius) to the apex circle. NFF gives negative radii the
// meaning "inside visible"; both radii <= 0 (not both 0) is kept with |r| and
// facing -1, a positive and a negative radius together is dropped.
struct ConeDesc {
  Vec3<float> base;
  float base_radius;
  Vec3<float> apex;
  float apex_radius;
};

}  // namespace quiver
