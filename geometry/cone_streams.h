// Cone streams per kernel unit (simd/isa.h), each compiled with that unit's flags.
#pragma once

#include "geometry/bvh_traversal.h"
#include "geometry/cone_soa.h"
#include "geometry/streams.h"

namespace quiver {

enum class ConeMethod { quadric };

template <KernelUnit U>
KernelStreams<ConeSoA> cone_streams(ConeMethod method);
template <>
KernelStreams<ConeSoA> cone_streams<KernelUnit::scalar>(ConeMethod method);
template <>
KernelStreams<ConeSoA> cone_streams<KernelUnit::scalar_fma>(ConeMethod method);
template <>
KernelStreams<ConeSoA> cone_streams<KernelUnit::sse4>(ConeMethod method);
template <>
KernelStreams<ConeSoA> cone_streams<KernelUnit::avx2>(ConeMethod method);
template <>
KernelStreams<ConeSoA> cone_streams<KernelUnit::avx512>(ConeMethod method);

// Traversal of a BVH over the store, per node width (geometry/bvh_traversal.h).
template <KernelUnit U>
BvhStreams<ConeSoA> cone_bvh_streams(ConeMethod method);
template <>
BvhStreams<ConeSoA> cone_bvh_streams<KernelUnit::scalar>(ConeMethod method);
template <>
BvhStreams<ConeSoA> cone_bvh_streams<KernelUnit::scalar_fma>(ConeMethod method);
template <>
BvhStreams<ConeSoA> cone_bvh_streams<KernelUnit::sse4>(ConeMethod method);
template <>
BvhStreams<ConeSoA> cone_bvh_streams<KernelUnit::avx2>(ConeMethod method);
template <>
BvhStreams<ConeSoA> cone_bvh_streams<KernelUnit::avx512>(ConeMethod method);

}  // namespace quiver
