// Compiled once per kernel unit (simd/kernel_units.h); QUIVER_KERNEL_UNIT names the unit.
#include "geometry/sphere_streams.h"

namespace quiver {

template <KernelUnit U>
KernelStreams<SphereSoA> sphere_streams(SphereMethod method) {
  switch (method) {
    case SphereMethod::algebraic: return make_streams<U, SphereAlgebraic, SphereSoA>();
    case SphereMethod::geometric: return make_streams<U, SphereGeometric, SphereSoA>();
    case SphereMethod::robust: break;
  }
  return make_streams<U, SphereRobust, SphereSoA>();
}

template <KernelUnit U>
BvhStreams<SphereSoA> sphere_bvh_streams(SphereMethod method) {
  switch (method) {
    case SphereMethod::algebraic: return make_bvh_streams<U, SphereAlgebraic, SphereSoA>();
    case SphereMethod::geometric: return make_bvh_streams<U, SphereGeometric, SphereSoA>();
    case SphereMethod::robust: break;
  }
  return make_bvh_streams<U, SphereRobust, SphereSoA>();
}

// This unit's instances.
template KernelStreams<SphereSoA> sphere_streams<kThisUnit>(SphereMethod);
template BvhStreams<SphereSoA> sphere_bvh_streams<kThisUnit>(SphereMethod);

}  // namespace quiver
