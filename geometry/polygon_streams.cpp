// Compiled once per ISA; QUIVER_LANE_WIDTH names this unit's width.
#include "geometry/polygon_streams.h"

namespace quiver {

template <>
KernelStreams<PolygonSoA> polygon_streams<QUIVER_LANE_WIDTH>(PolygonMethod method) {
  using F = Lanes<QUIVER_LANE_WIDTH>;
  switch (method) {
    case PolygonMethod::crossing: break;
  }
  return make_packet_streams<F, PolygonCrossing, PolygonSoA>();
}

}  // namespace quiver
