// Smooth shading normals for a triangle mesh that has none: angle-weighted
// vertex normals (Thürmer and Wüthrich, "Computing vertex normals from
// polygonal meshes", JGT 1998) with a crease angle. The normal of corner k
// of triangle t, at vertex v, is the sum over the triangles around v whose
// unit normals lie within the crease angle of t's own, each weighted by
// its corner angle at v, then normalised: faces meeting at an edge sharper
// than the crease angle keep their own normals there, so hard edges stay
// hard. Triangles share a vertex when they name the same position index
// (no welding by distance). Computed in double; a triangle of zero area
// contributes nothing and gets no normals.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>

#include "simd/vec3.h"

namespace quiver {

// Degrees; 0 is faceted (no smoothing), 180 smooths across every edge.
inline constexpr double kDefaultCreaseAngleDegrees = 60.0;
inline constexpr double kMaxCreaseAngleDegrees = 180.0;
// The crease test is pairwise among the triangles around a vertex, so a
// vertex shared by more triangles than this keeps each corner's face
// normal: at most this many tests per corner, whatever the input.
inline constexpr std::size_t kMaxSmoothedValence = 256;

// A triangle as three indices into a position array.
using TriangleIndices = std::array<std::uint32_t, 3>;
using CornerNormals = std::array<Vec3<float>, 3>;

// true when crease_angle_degrees is in [0, kMaxCreaseAngleDegrees].
bool valid_crease_angle(double crease_angle_degrees);

// The unit normals of each triangle's three corners, handed to
// write_smoothed(triangle, normals) (once a triangle, from any thread) where
// they are not all its face normal; a triangle not handed stays faceted: a
// zero-area triangle, every triangle when the crease angle is 0, and a
// triangle whose every corner normal rounds to its face normal (no
// neighbour within the crease angle, or only coplanar ones), so flat parts
// shade exactly as before.
// Throws std::invalid_argument for an index out of range or a crease angle
// outside [0, 180], and std::length_error for 2^32 / 3 triangles or more.
// Memory is linear in the mesh: a few words per position and per triangle.
void smooth_vertex_normals(std::span<const Vec3<float>> positions, std::span<const TriangleIndices> triangles,
                           double crease_angle_degrees,
                           const std::function<void(std::size_t, const CornerNormals&)>& write_smoothed);

}  // namespace quiver
