// Triangle streams per kernel unit (simd/isa.h), each compiled with that unit's flags.
#pragma once

#include "geometry/bvh_traversal.h"
#include "geometry/streams.h"
#include "geometry/triangle_soa.h"

namespace quiver {

enum class TriangleMethod { moller_trumbore, watertight };

template <KernelUnit U>
KernelStreams<TriangleSoA> triangle_streams(TriangleMethod method);
template <>
KernelStreams<TriangleSoA> triangle_streams<KernelUnit::scalar>(TriangleMethod method);
template <>
KernelStreams<TriangleSoA> triangle_streams<KernelUnit::scalar_fma>(TriangleMethod method);
template <>
KernelStreams<TriangleSoA> triangle_streams<KernelUnit::sse4>(TriangleMethod method);
template <>
KernelStreams<TriangleSoA> triangle_streams<KernelUnit::avx2>(TriangleMethod method);
template <>
KernelStreams<TriangleSoA> triangle_streams<KernelUnit::avx512>(TriangleMethod method);

// Traversal of a BVH over the store, per node width (geometry/bvh_traversal.h).
template <KernelUnit U>
BvhStreams<TriangleSoA> triangle_bvh_streams(TriangleMethod method);
template <>
BvhStreams<TriangleSoA> triangle_bvh_streams<KernelUnit::scalar>(TriangleMethod method);
template <>
BvhStreams<TriangleSoA> triangle_bvh_streams<KernelUnit::scalar_fma>(TriangleMethod method);
template <>
BvhStreams<TriangleSoA> triangle_bvh_streams<KernelUnit::sse4>(TriangleMethod method);
template <>
BvhStreams<TriangleSoA> triangle_bvh_streams<KernelUnit::avx2>(TriangleMethod method);
template <>
BvhStreams<TriangleSoA> triangle_bvh_streams<KernelUnit::avx512>(TriangleMethod method);

}  // namespace quiver
