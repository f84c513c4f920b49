// Compiled once per ISA; QUIVER_LANE_WIDTH names this unit's width.
#include "geometry/cone_streams.h"

namespace quiver {

template <>
KernelStreams<ConeSoA> cone_streams<QUIVER_LANE_WIDTH>(ConeMethod method) {
  using F = Lanes<QUIVER_LANE_WIDTH>;
  switch (method) {
    case ConeMethod::quadric: break;
  }
  return make_streams<F, ConeQuadric, ConeSoA>();
}

}  // namespace quiver
