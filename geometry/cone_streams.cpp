// Compiled once per kernel unit (simd/kernel_units.h); QUIVER_KERNEL_UNIT names the unit.
#include "geometry/cone_streams.h"

namespace quiver {

template <KernelUnit U>
KernelStreams<ConeSoA> cone_streams(ConeMethod method) {
  switch (method) {
    case ConeMethod::quadric: break;
  }
  return make_packet_streams<U, ConeQuadric, ConeSoA>();
}

template <KernelUnit U>
BvhStreams<ConeSoA> cone_bvh_streams(ConeMethod method) {
  switch (method) {
    case ConeMethod::quadric: break;
  }
  return make_bvh_streams<U, ConeQuadric, ConeSoA>();
}

// This unit's instances.
template KernelStreams<ConeSoA> cone_streams<kThisUnit>(ConeMethod);
template BvhStreams<ConeSoA> cone_bvh_streams<kThisUnit>(ConeMethod);

}  // namespace quiver
