// Compiled once per kernel unit; QUIVER_KERNEL_UNIT names the unit.
#include "geometry/cone_streams.h"

namespace quiver {

template <>
KernelStreams<ConeSoA> cone_streams<kThisUnit>(ConeMethod method) {
  switch (method) {
    case ConeMethod::quadric: break;
  }
  return make_streams<kThisUnit, ConeQuadric, ConeSoA>();
}

template <>
BvhStreams<ConeSoA> cone_bvh_streams<kThisUnit>(ConeMethod method) {
  switch (method) {
    case ConeMethod::quadric: break;
  }
  return make_bvh_streams<kThisUnit, ConeQuadric, ConeSoA>();
}

}  // namespace quiver
