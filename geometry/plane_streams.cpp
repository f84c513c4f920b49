// Compiled once per ISA; QUIVER_LANE_WIDTH names this unit's width.
#include "geometry/plane_streams.h"

namespace quiver {

template <>
KernelStreams<PlaneSoA> plane_streams<QUIVER_LANE_WIDTH>(PlaneMethod method) {
  using F = Lanes<QUIVER_LANE_WIDTH>;
  switch (method) {
    case PlaneMethod::seed: break;
  }
  return make_streams<F, PlaneSeed, PlaneSoA>();
}

}  // namespace quiver
