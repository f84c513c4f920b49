// Compiled once per kernel unit (simd/kernel_units.h); QUIVER_KERNEL_UNIT names the unit.
#include "geometry/plane_streams.h"

namespace quiver {

template <KernelUnit U>
KernelStreams<PlaneSoA> plane_streams(PlaneMethod method) {
  switch (method) {
    case PlaneMethod::anchored: return make_packet_streams<U, PlaneAnchored, PlaneSoA>();
    case PlaneMethod::seed: break;
  }
  throw_study_method("plane", "seed");
}

// This unit's instances.
template KernelStreams<PlaneSoA> plane_streams<kThisUnit>(PlaneMethod);

}  // namespace quiver
