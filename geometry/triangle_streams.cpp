// Compiled once per kernel unit (simd/kernel_units.h); QUIVER_KERNEL_UNIT names the unit.
#include "geometry/triangle_streams.h"

namespace quiver {

template <KernelUnit U>
KernelStreams<TriangleSoA> triangle_streams(TriangleMethod method) {
  switch (method) {
    case TriangleMethod::watertight: return make_packet_streams<U, TriangleWatertight, TriangleSoA>();
    case TriangleMethod::moller_trumbore: break;
  }
  throw_study_method("triangle", "moller_trumbore");
}

template <KernelUnit U>
BvhStreams<TriangleSoA> triangle_bvh_streams(TriangleMethod method) {
  switch (method) {
    case TriangleMethod::watertight: return make_bvh_streams<U, TriangleWatertight, TriangleSoA>();
    case TriangleMethod::moller_trumbore: break;
  }
  throw_study_method("triangle", "moller_trumbore");
}

// This unit's instances.
template KernelStreams<TriangleSoA> triangle_streams<kThisUnit>(TriangleMethod);
template BvhStreams<TriangleSoA> triangle_bvh_streams<kThisUnit>(TriangleMethod);

}  // namespace quiver
