// Compiled once per kernel unit (simd/kernel_units.h); QUIVER_KERNEL_UNIT names the unit.
#include "geometry/polygon_streams.h"

namespace quiver {

template <KernelUnit U>
KernelStreams<PolygonSoA> polygon_streams(PolygonMethod method) {
  switch (method) {
    case PolygonMethod::crossing: break;
  }
  return make_packet_streams<U, PolygonCrossing, PolygonSoA>();
}

template <KernelUnit U>
BvhStreams<PolygonSoA> polygon_bvh_streams(PolygonMethod method) {
  switch (method) {
    case PolygonMethod::crossing: break;
  }
  return make_bvh_streams<U, PolygonCrossing, PolygonSoA>();
}

// This unit's instances.
template KernelStreams<PolygonSoA> polygon_streams<kThisUnit>(PolygonMethod);
template BvhStreams<PolygonSoA> polygon_bvh_streams<kThisUnit>(PolygonMethod);

}  // namespace quiver
