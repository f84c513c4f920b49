// Plane streams per lane width (1, 4, 8), each compiled in its ISA's unit.
#pragma once

#include "geometry/plane_soa.h"
#include "geometry/streams.h"

namespace quiver {

enum class PlaneMethod { seed };

template <int W>
KernelStreams<PlaneSoA> plane_streams(PlaneMethod method);
template <>
KernelStreams<PlaneSoA> plane_streams<1>(PlaneMethod method);
template <>
KernelStreams<PlaneSoA> plane_streams<4>(PlaneMethod method);
template <>
KernelStreams<PlaneSoA> plane_streams<8>(PlaneMethod method);

}  // namespace quiver
