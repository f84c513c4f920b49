// Welding by exact position: the vertices of a mesh that share a position
// (-0 counted as +0) get one index, for normals smoothed across files that
// share no vertices (STL) or split them at seams.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "simd/vec3.h"

namespace quiver {

struct WeldedPositions {
  std::vector<std::uint32_t> index_of;  // per input vertex: its position's index
  std::vector<Vec3<float>> positions;   // the distinct positions (-0 as +0)
};

// Welds position_at(0 .. count - 1) (count below 2^32), each position asked
// for once, from any thread. The distinct positions are numbered in the
// order of the first vertex holding each, as a serial welder would: the
// same numbers for any thread count.
WeldedPositions weld_positions(std::size_t count, const std::function<Vec3<float>(std::size_t)>& position_at);

// Renumbers `positions` in the order the triangles (indices into it) first
// use them, dropping those none uses, and the triangles' indices alike: the
// numbering a welder visiting the triangles' corners in order would give,
// whose nearby numbers keep per-vertex arrays local to the triangles.
void number_by_first_use(std::vector<Vec3<float>>& positions, std::span<std::array<std::uint32_t, 3>> triangles);

}  // namespace quiver
