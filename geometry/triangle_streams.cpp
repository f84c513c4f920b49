// Compiled once per kernel unit (simd/kernel_units.h); QUIVER_KERNEL_UNIT names the unit.
#include "geometry/triangle_streams.h"

namespace quiver {

template <KernelUnit U>
KernelStreams<TriangleSoA> triangle_streams(TriangleMethod method) {
  switch (method) {
    case TriangleMethod::moller_trumbore: return make_streams<U, TriangleMollerTrumbore, TriangleSoA>();
    case TriangleMethod::watertight: return make_streams<U, TriangleWatertight, TriangleSoA>();
  }
  return make_streams<U, TriangleMollerTrumbore, TriangleSoA>();
}

template <KernelUnit U>
BvhStreams<TriangleSoA> triangle_bvh_streams(TriangleMethod method) {
  switch (method) {
    case TriangleMethod::moller_trumbore: return make_bvh_streams<U, TriangleMollerTrumbore, TriangleSoA>();
    case TriangleMethod::watertight: break;
  }
  return make_bvh_streams<U, TriangleWatertight, TriangleSoA>();
}

// This unit's instances.
template KernelStreams<TriangleSoA> triangle_streams<kThisUnit>(TriangleMethod);
template BvhStreams<TriangleSoA> triangle_bvh_streams<kThisUnit>(TriangleMethod);

}  // namespace quiver
