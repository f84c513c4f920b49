// Infinite planes in SoA: unit normal (nx, ny, nz) and offset d.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "geometry/build_report.h"
#include "geometry/primitive_desc.h"
#include "geometry/plane.h"
#include "geometry/soa.h"

namespace quiver {

struct PlaneSoA {
  AlignedFloats nx, ny, nz, d;
  std::size_t count = 0;
  // Input index of each kept primitive (builders drop some), and the id of
  // primitive 0 in hits (a scene numbers its stores consecutively).
  std::vector<std::uint32_t> source;
  std::int32_t id_base = 0;

  std::size_t size() const { return count; }
  template <class F>
  PlaneLanes<F> broadcast(std::size_t i) const {
    return {broadcast_vec3<F>(nx, ny, nz, i), F(d[i])};
  }
  template <class F>
  PlaneLanes<F> load(std::size_t first) const {
    return {load_vec3_unaligned<F>(nx, ny, nz, first), load_lanes_unaligned<F>(d.data() + first)};
  }
};

// Drops planes with a non-finite number or a zero (or underflowing) normal.
PlaneSoA build_planes(std::span<const PlaneDesc> planes, BuildReport& report);

}  // namespace quiver
