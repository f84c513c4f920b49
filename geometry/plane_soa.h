// Infinite planes in SoA: unit normal (nx, ny, nz), offset d = -n.p in
// float (the seed's formula) and the point p as given (px, py, pz).
#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "geometry/build_report.h"
#include "geometry/primitive_desc.h"
#include "geometry/plane.h"
#include "geometry/soa.h"

namespace quiver {

struct PlaneSoA {
  AlignedFloats nx, ny, nz, d, px, py, pz;
  std::size_t count = 0;
  // Input index of each kept primitive (builders drop some), and the id of
  // primitive 0 in hits (a scene numbers its stores consecutively).
  std::vector<std::uint32_t> source;
  std::int32_t id_base = 0;

  std::size_t size() const { return count; }
  std::vector<AlignedFloats*> columns() { return {&nx, &ny, &nz, &d, &px, &py, &pz}; }
  // Bytes held by the columns and the source list.
  std::size_t memory_bytes() const;
  template <class F>
  PlaneLanes<F> broadcast(std::size_t i) const {
    return {broadcast_vec3<F>(nx, ny, nz, i), F(d[i]), broadcast_vec3<F>(px, py, pz, i)};
  }
  template <class F>
  PlaneLanes<F> load(std::size_t first) const {
    return {load_vec3_unaligned<F>(nx, ny, nz, first), load_lanes_unaligned<F>(d.data() + first),
            load_vec3_unaligned<F>(px, py, pz, first)};
  }
};

// Drops planes with a non-finite number or a zero (or underflowing) normal.
PlaneSoA build_planes(std::span<const PlaneDesc> planes, BuildReport& report);

// The plane in the scene's list of kinds (geometry/kinds.h): unbounded, so
// scanned, never in a BVH.
struct PlaneKind {
  static constexpr std::string_view name = "plane", plural = "planes";
  static constexpr bool bounded = false;
  using Method = PlaneMethod;
  static constexpr PlaneMethod product_method = PlaneMethod::anchored;
  using Desc = PlaneDesc;
  using Store = PlaneSoA;
  static Store build(std::span<const Desc> descs, BuildReport& report) { return build_planes(descs, report); }
};

}  // namespace quiver
