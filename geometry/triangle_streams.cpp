// Compiled once per kernel unit; QUIVER_KERNEL_UNIT names the unit.
#include "geometry/triangle_streams.h"

namespace quiver {

template <>
KernelStreams<TriangleSoA> triangle_streams<kThisUnit>(TriangleMethod method) {
  switch (method) {
    case TriangleMethod::moller_trumbore: return make_streams<kThisUnit, TriangleMollerTrumbore, TriangleSoA>();
    case TriangleMethod::watertight: return make_streams<kThisUnit, TriangleWatertight, TriangleSoA>();
  }
  return make_streams<kThisUnit, TriangleMollerTrumbore, TriangleSoA>();
}

template <>
BvhStreams<TriangleSoA> triangle_bvh_streams<kThisUnit>(TriangleMethod method) {
  switch (method) {
    case TriangleMethod::moller_trumbore: return make_bvh_streams<kThisUnit, TriangleMollerTrumbore, TriangleSoA>();
    case TriangleMethod::watertight: break;
  }
  return make_bvh_streams<kThisUnit, TriangleWatertight, TriangleSoA>();
}

}  // namespace quiver
