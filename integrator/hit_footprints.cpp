// Hit footprints in packets (the contract: hit_footprints.h). Compiled once
// per kernel unit; F is the unit's lane type.
#include "integrator/hit_footprints.h"

#include "integrator/ray_differentials.h"

namespace quiver {

template <KernelUnit U>
void hit_footprints(const RaySoA& rays, const HitSoA& hits, const DifferentialColumns& differentials,
                    Vec3Columns& point_dx, Vec3Columns& point_dy) {
  using F = UnitLanes<U>;
  const Vec3<F> none(F(0.f), F(0.f), F(0.f));
  for (std::size_t first = 0; first < rays.count; first += std::size_t(lane_count<F>)) {
    const Ray<F> ray = rays.load<F>(first);
    const Hit<F> hit = hits.load<F>(first);
    const Mask<F> met = first_lanes<F>(rays.count - first) & nonzero_lanes(hit.id - IntLanes<F>(kNoHit));
    const auto transfer = [&](const Vec3Columns& d_origin, const Vec3Columns& d_direction) {
      return select(met,
                    transfer_differential(d_origin.load<F>(first), d_direction.load<F>(first), ray.direction,
                                          hit.t, hit.ng),
                    none);
    };
    point_dx.store(first, transfer(differentials.origin_dx, differentials.direction_dx));
    point_dy.store(first, transfer(differentials.origin_dy, differentials.direction_dy));
  }
}

template void hit_footprints<kThisUnit>(const RaySoA&, const HitSoA&, const DifferentialColumns&, Vec3Columns&,
                                        Vec3Columns&);

}  // namespace quiver
