// Compiled once per kernel unit (simd/kernel_units.h); QUIVER_KERNEL_UNIT names the unit.
#include "geometry/sphere_streams.h"

namespace quiver {

template <KernelUnit U>
KernelStreams<SphereSoA> sphere_streams(SphereMethod method) {
  switch (method) {
    case SphereMethod::algebraic: return make_packet_streams<U, SphereAlgebraic, SphereSoA>();
    case SphereMethod::robust: return make_packet_streams<U, SphereRobust, SphereSoA>();
    case SphereMethod::geometric: break;
  }
  throw_study_method("sphere", "geometric");
}

template <KernelUnit U>
BvhStreams<SphereSoA> sphere_bvh_streams(SphereMethod method) {
  switch (method) {
    case SphereMethod::algebraic: return make_bvh_streams<U, SphereAlgebraic, SphereSoA>();
    case SphereMethod::robust: return make_bvh_streams<U, SphereRobust, SphereSoA>();
    case SphereMethod::geometric: break;
  }
  throw_study_method("sphere", "geometric");
}

// This unit's instances.
template KernelStreams<SphereSoA> sphere_streams<kThisUnit>(SphereMethod);
template BvhStreams<SphereSoA> sphere_bvh_streams<kThisUnit>(SphereMethod);

}  // namespace quiver
