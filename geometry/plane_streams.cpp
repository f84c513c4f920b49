// Compiled once per kernel unit (simd/kernel_units.h); QUIVER_KERNEL_UNIT names the unit.
#include "geometry/plane_streams.h"

namespace quiver {

template <KernelUnit U>
KernelStreams<PlaneSoA> plane_streams(PlaneMethod method) {
  switch (method) {
    case PlaneMethod::seed: return make_streams<U, PlaneSeed, PlaneSoA>();
    case PlaneMethod::anchored: break;
  }
  return make_streams<U, PlaneAnchored, PlaneSoA>();
}

// This unit's instances.
template KernelStreams<PlaneSoA> plane_streams<kThisUnit>(PlaneMethod);

}  // namespace quiver
