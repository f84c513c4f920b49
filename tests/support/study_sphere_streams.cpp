// Compiled once per kernel unit (simd/kernel_units.h), like the product's kernels.
#include "tests/support/study_streams.h"

namespace quiver {

template <KernelUnit U>
KernelStreams<SphereSoA> study_sphere_streams(SphereMethod method) {
  switch (method) {
    case SphereMethod::algebraic: return make_streams<U, SphereAlgebraic, SphereSoA>();
    case SphereMethod::geometric: return make_streams<U, SphereGeometric, SphereSoA>();
    case SphereMethod::robust: break;
  }
  return make_streams<U, SphereRobust, SphereSoA>();
}

template <KernelUnit U>
BvhStreams<SphereSoA> study_sphere_bvh_streams(SphereMethod method) {
  if (method == SphereMethod::geometric) return make_bvh_streams<U, SphereGeometric, SphereSoA>();
  if (method == SphereMethod::algebraic) return with_study_widths<U, SphereAlgebraic>(product_streams_of<U, SphereKind>(method).tree);
  return with_study_widths<U, SphereRobust>(product_streams_of<U, SphereKind>(method).tree);
}

template KernelStreams<SphereSoA> study_sphere_streams<kThisUnit>(SphereMethod);
template BvhStreams<SphereSoA> study_sphere_bvh_streams<kThisUnit>(SphereMethod);

}  // namespace quiver
