// The footprint of each hit of a wave: the hit point's change over one
// sample spacing along film x and y, each ray's differentials
// (integrator/ray_differentials.h) carried to its hit's plane by
// transfer_differential. In the unit's lanes (integrator/hit_footprints.cpp,
// compiled per kernel unit), the same formula as one ray at a time, so
// every width gives the same bits; a miss's change is 0.
#pragma once

#include "geometry/soa.h"
#include "integrator/wave.h"

namespace quiver {

// point_dx and point_dy (padded like rays) hold the change of each of the
// first rays.count rays' hit point; differentials as carried by the rays.
template <KernelUnit U>
void hit_footprints(const RaySoA& rays, const HitSoA& hits, const DifferentialColumns& differentials,
                    Vec3Columns& point_dx, Vec3Columns& point_dy);

using HitFootprintsFunction = void (*)(const RaySoA&, const HitSoA&, const DifferentialColumns&, Vec3Columns&,
                                       Vec3Columns&);

}  // namespace quiver
