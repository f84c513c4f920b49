// Spheres in SoA: center (cx, cy, cz), r^2 and 1/r.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "geometry/build_report.h"
#include "geometry/primitive_desc.h"
#include "geometry/soa.h"
#include "geometry/sphere.h"

namespace quiver {

struct SphereSoA {
  AlignedFloats cx, cy, cz, r2, inv_r;
  std::size_t count = 0;
  // Input index of each kept primitive (builders drop some), and the id of
  // primitive 0 in hits (a scene numbers its stores consecutively).
  std::vector<std::uint32_t> source;
  std::int32_t id_base = 0;

  std::size_t size() const { return count; }
  std::size_t memory_bytes() const;  // columns and source list
  template <class F>
  SphereLanes<F> broadcast(std::size_t i) const {
    return {broadcast_vec3<F>(cx, cy, cz, i), F(r2[i]), F(inv_r[i])};
  }
  template <class F>
  SphereLanes<F> load(std::size_t first) const {
    return {load_vec3_unaligned<F>(cx, cy, cz, first), load_lanes_unaligned<F>(r2.data() + first),
            load_lanes_unaligned<F>(inv_r.data() + first)};
  }
};

// Drops spheres with a non-finite center or radius, or whose r^2 overflows
// (non-finite); and spheres with a radius <= 0 or whose r^2 is below the
// smallest normal float (degenerate). Negative radii are not mirrored.
SphereSoA build_spheres(std::span<const SphereDesc> spheres, BuildReport& report);

// The sphere in the scene's list of kinds (geometry/kinds.h).
struct SphereKind {
  static constexpr std::string_view name = "sphere", plural = "spheres";
  static constexpr bool bounded = true;
  using Method = SphereMethod;
  // The default; a scene whose rays all start near its spheres may take
  // the algebraic test (integrator/scene_intersector.h).
  static constexpr SphereMethod product_method = SphereMethod::robust;
  using Desc = SphereDesc;
  using Store = SphereSoA;
  static Store build(std::span<const Desc> descs, BuildReport& report) { return build_spheres(descs, report); }
};

}  // namespace quiver
