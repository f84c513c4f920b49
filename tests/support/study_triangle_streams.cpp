// Compiled once per kernel unit (simd/kernel_units.h), like the product's kernels.
#include "tests/support/study_streams.h"

namespace quiver {

template <KernelUnit U>
KernelStreams<TriangleSoA> study_triangle_streams(TriangleMethod method) {
  switch (method) {
    case TriangleMethod::moller_trumbore: return make_streams<U, TriangleMollerTrumbore, TriangleSoA>();
    case TriangleMethod::watertight: break;
  }
  return make_streams<U, TriangleWatertight, TriangleSoA>();
}

template <KernelUnit U>
BvhStreams<TriangleSoA> study_triangle_bvh_streams(TriangleMethod method) {
  if (method == TriangleMethod::moller_trumbore) return make_bvh_streams<U, TriangleMollerTrumbore, TriangleSoA>();
  return with_study_widths<U, TriangleWatertight>(product_streams_of<U, TriangleKind>(method).tree);
}

template KernelStreams<TriangleSoA> study_triangle_streams<kThisUnit>(TriangleMethod);
template BvhStreams<TriangleSoA> study_triangle_bvh_streams<kThisUnit>(TriangleMethod);

}  // namespace quiver
