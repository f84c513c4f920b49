// Compiled once per ISA; QUIVER_LANE_WIDTH names this unit's width.
#include "geometry/triangle_streams.h"

namespace quiver {

template <>
KernelStreams<TriangleSoA> triangle_streams<QUIVER_LANE_WIDTH>(TriangleMethod method) {
  using F = Lanes<QUIVER_LANE_WIDTH>;
  switch (method) {
    case TriangleMethod::moller_trumbore: return make_streams<F, TriangleMollerTrumbore, TriangleSoA>();
    case TriangleMethod::watertight: return make_streams<F, TriangleWatertight, TriangleSoA>();
  }
  return make_streams<F, TriangleMollerTrumbore, TriangleSoA>();
}

}  // namespace quiver
