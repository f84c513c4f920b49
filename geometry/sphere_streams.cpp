// Compiled once per ISA; QUIVER_LANE_WIDTH names this unit's width.
#include "geometry/sphere_streams.h"

namespace quiver {

template <>
KernelStreams<SphereSoA> sphere_streams<QUIVER_LANE_WIDTH>(SphereMethod method) {
  using F = Lanes<QUIVER_LANE_WIDTH>;
  switch (method) {
    case SphereMethod::algebraic: return make_streams<F, SphereAlgebraic, SphereSoA>();
    case SphereMethod::geometric: return make_streams<F, SphereGeometric, SphereSoA>();
    case SphereMethod::robust: break;
  }
  return make_streams<F, SphereRobust, SphereSoA>();
}

}  // namespace quiver
