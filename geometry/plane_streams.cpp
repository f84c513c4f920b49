// Compiled once per kernel unit; QUIVER_KERNEL_UNIT names the unit.
#include "geometry/plane_streams.h"

namespace quiver {

template <>
KernelStreams<PlaneSoA> plane_streams<kThisUnit>(PlaneMethod method) {
  switch (method) {
    case PlaneMethod::seed: break;
  }
  return make_streams<kThisUnit, PlaneSeed, PlaneSoA>();
}

}  // namespace quiver
