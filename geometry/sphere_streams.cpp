// Compiled once per kernel unit; QUIVER_KERNEL_UNIT names the unit.
#include "geometry/sphere_streams.h"

namespace quiver {

template <>
KernelStreams<SphereSoA> sphere_streams<kThisUnit>(SphereMethod method) {
  switch (method) {
    case SphereMethod::algebraic: return make_streams<kThisUnit, SphereAlgebraic, SphereSoA>();
    case SphereMethod::geometric: return make_streams<kThisUnit, SphereGeometric, SphereSoA>();
    case SphereMethod::robust: break;
  }
  return make_streams<kThisUnit, SphereRobust, SphereSoA>();
}

template <>
BvhStreams<SphereSoA> sphere_bvh_streams<kThisUnit>(SphereMethod method) {
  switch (method) {
    case SphereMethod::algebraic: return make_bvh_streams<kThisUnit, SphereAlgebraic, SphereSoA>();
    case SphereMethod::geometric: return make_bvh_streams<kThisUnit, SphereGeometric, SphereSoA>();
    case SphereMethod::robust: break;
  }
  return make_bvh_streams<kThisUnit, SphereRobust, SphereSoA>();
}

}  // namespace quiver
