// Triangles in SoA: vertex columns v0, v1, v2 (9), and optional per-vertex
// shading normals (9) and texture coordinates (6), empty when no input
// triangle has them.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "geometry/build_report.h"
#include "geometry/primitive_desc.h"
#include "geometry/soa.h"
#include "geometry/triangle.h"

namespace quiver {

struct TriangleSoA {
  AlignedFloats v0x, v0y, v0z, v1x, v1y, v1z, v2x, v2y, v2z;
  AlignedFloats n0x, n0y, n0z, n1x, n1y, n1z, n2x, n2y, n2z;  // unit, or empty
  AlignedFloats uv0u, uv0v, uv1u, uv1v, uv2u, uv2v;            // or empty
  std::size_t count = 0;
  // Input index of each kept primitive (builders drop some), and the id of
  // primitive 0 in hits (a scene numbers its stores consecutively).
  std::vector<std::uint32_t> source;
  std::int32_t id_base = 0;

  // BVH traversal: incoherent packets go ray by ray (geometry/bvh/bvh_streams.h).
  static constexpr bool kIncoherentRaysTraverseAlone = true;

  std::size_t size() const { return count; }
  bool has_normals() const { return !n0x.empty(); }
  bool has_uvs() const { return !uv0u.empty(); }

  template <class F>
  TriangleLanes<F> broadcast(std::size_t i) const {
    return {broadcast_vec3<F>(v0x, v0y, v0z, i), broadcast_vec3<F>(v1x, v1y, v1z, i),
            broadcast_vec3<F>(v2x, v2y, v2z, i)};
  }
  template <class F>
  TriangleLanes<F> load(std::size_t first) const {
    return {load_vec3_unaligned<F>(v0x, v0y, v0z, first), load_vec3_unaligned<F>(v1x, v1y, v1z, first),
            load_vec3_unaligned<F>(v2x, v2y, v2z, first)};
  }
  // Vertex k (0, 1, 2) of triangle i.
  Vec3<float> vertex(std::size_t i, int k) const;
  // Shading normal at vertex k; requires has_normals().
  Vec3<float> normal(std::size_t i, int k) const;
  // Texture coordinates at vertex k; requires has_uvs().
  std::array<float, 2> uv(std::size_t i, int k) const;
  // Every column, for padding and checks (the optional ones may be empty).
  std::vector<AlignedFloats*> columns();
  std::size_t memory_bytes() const;  // columns and source list
};

// Smallest height / longest edge a kept triangle may have: below half a float
// ulp of the longest edge a triangle is a segment for a float kernel.
inline constexpr double kMinTriangleRelativeHeight = 0x1p-24;

// Drops triangles with a non-finite number (vertex, normal, uv, or an edge or
// normal that overflows) and degenerate ones: zero area (repeated vertex,
// collinear vertices), height below kMinTriangleRelativeHeight times the
// longest edge (computed in double), or a float edge cross product that is
// exactly zero. When some triangles have normals (uvs) and others do not,
// the others get the unit geometric normal (uvs (0,0), (1,0), (0,1)); a zero
// shading normal is replaced by the geometric one; normals are normalised.
TriangleSoA build_triangles(std::span<const TriangleDesc> triangles, BuildReport& report);

// Triangles of an indexed mesh, in index order, without normals or uvs.
// Throws std::out_of_range for an index past positions.
std::vector<TriangleDesc> triangles_from_indexed(std::span<const Vec3<float>> positions,
                                                 std::span<const std::array<std::uint32_t, 3>> indices);

// The triangle in the scene's list of kinds (geometry/kinds.h).
struct TriangleKind {
  static constexpr std::string_view name = "triangle", plural = "triangles";
  static constexpr bool bounded = true;
  using Method = TriangleMethod;
  static constexpr TriangleMethod product_method = TriangleMethod::watertight;
  using Desc = TriangleDesc;
  using Store = TriangleSoA;
  static Store build(std::span<const Desc> descs, BuildReport& report) { return build_triangles(descs, report); }
};

}  // namespace quiver
