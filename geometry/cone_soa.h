// Open cones and cylinders in SoA: base center, unit axis, height, base
// radius, slope and facing (see geometry/cone.h).
#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "geometry/build_report.h"
#include "geometry/primitive_desc.h"
#include "geometry/cone.h"
#include "geometry/soa.h"

namespace quiver {

struct ConeSoA {
  AlignedFloats bx, by, bz, ax, ay, az, height, radius0, slope, facing;
  std::size_t count = 0;
  // Input index of each kept primitive (builders drop some), and the id of
  // primitive 0 in hits (a scene numbers its stores consecutively).
  std::vector<std::uint32_t> source;
  std::int32_t id_base = 0;

  std::size_t size() const { return count; }
  std::size_t memory_bytes() const;  // columns and source list
  template <class F>
  ConeLanes<F> broadcast(std::size_t i) const {
    return {broadcast_vec3<F>(bx, by, bz, i), broadcast_vec3<F>(ax, ay, az, i), F(height[i]),
            F(radius0[i]),                    F(slope[i]),                      F(facing[i])};
  }
  template <class F>
  ConeLanes<F> load(std::size_t first) const {
    return {load_vec3_unaligned<F>(bx, by, bz, first),          load_vec3_unaligned<F>(ax, ay, az, first),
            load_lanes_unaligned<F>(height.data() + first),     load_lanes_unaligned<F>(radius0.data() + first),
            load_lanes_unaligned<F>(slope.data() + first),      load_lanes_unaligned<F>(facing.data() + first)};
  }
};

// Drops cones with a non-finite number (in the input or in the derived axis
// length) as non-finite; a zero (or subnormal) axis, both radii zero, radii of
// mixed sign, or a radius, slope or squared radius/slope that over- or
// underflows as degenerate.
ConeSoA build_cones(std::span<const ConeDesc> cones, BuildReport& report);

// The cone in the scene's list of kinds (geometry/kinds.h).
struct ConeKind {
  static constexpr std::string_view name = "cone", plural = "cones";
  static constexpr bool bounded = true;
  using Method = ConeMethod;
  static constexpr ConeMethod product_method = ConeMethod::quadric;
  using Desc = ConeDesc;
  using Store = ConeSoA;
  static Store build(std::span<const Desc> descs, BuildReport& report) { return build_cones(descs, report); }
};

}  // namespace quiver
