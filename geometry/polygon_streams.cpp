// Compiled once per kernel unit; QUIVER_KERNEL_UNIT names the unit.
#include "geometry/polygon_streams.h"

namespace quiver {

template <>
KernelStreams<PolygonSoA> polygon_streams<kThisUnit>(PolygonMethod method) {
  switch (method) {
    case PolygonMethod::crossing: break;
  }
  return make_packet_streams<kThisUnit, PolygonCrossing, PolygonSoA>();
}

template <>
BvhStreams<PolygonSoA> polygon_bvh_streams<kThisUnit>(PolygonMethod method) {
  switch (method) {
    case PolygonMethod::crossing: break;
  }
  return make_bvh_streams<kThisUnit, PolygonCrossing, PolygonSoA>();
}

}  // namespace quiver
