// Stress distributions for the accuracy study: one primitive of a kind and
// rays toward it, built in double and rounded to float once.
//   distance: origin at `parameter` sizes from a size-1 primitive near the
//             world origin (2 .. 1e7);
//   size:     the whole case scaled by `parameter` (1e-12 .. 1e12, tiny and
//             huge primitives), origin 10 sizes away;
//   far:      a size-1 primitive `parameter` from the world origin
//             (1 .. 1e7), origin 10 sizes from it;
//   grazing:  lines within `parameter` (1e-1 .. 1e-7, relative) of the
//             silhouette (sphere, cone) or at `parameter` radians to the
//             surface (plane, triangle, polygon), origin 10 sizes away.
// Primitives: sphere of radius s; plane through the center; triangle of
// circumradius about s; a concave 10-vertex star polygon of radius s in a
// plane whose slopes (1/2, 1/4) are exact in float; a truncated cone of
// radius s tapering to s/2 over height 2s. Directions are random (fixed
// seeds) and aimed so that about half of the rays hit; the oracle, not the
// construction, says which do.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bench/accuracy/methods.h"

namespace quiver::accuracy {

enum class Distribution { distance, size, far, grazing };

std::string_view distribution_name(Distribution d);
// The sweep's parameters, from easy to hard.
std::vector<double> sweep_parameters(Distribution d);

struct Case {
  Distribution distribution;
  double parameter;
  Primitives prims;  // empty when the kind cannot be built there (a far polygon is not planar in float)
  RaySoA rays;
};

Case make_case(Kind kind, Distribution distribution, double parameter, std::size_t ray_count, std::uint32_t seed);

// 64 primitives of a kind in [-8, 8]^3 and 4096 rays toward them from 30
// away, for timing tests per second.
Case make_timing_case(Kind kind, std::uint32_t seed);

}  // namespace quiver::accuracy
