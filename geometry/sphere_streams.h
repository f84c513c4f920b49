// Sphere streams per kernel unit (simd/isa.h), each compiled with that unit's flags.
#pragma once

#include "geometry/bvh_traversal.h"
#include "geometry/sphere_soa.h"
#include "geometry/streams.h"

namespace quiver {

enum class SphereMethod { algebraic, geometric, robust };

template <KernelUnit U>
KernelStreams<SphereSoA> sphere_streams(SphereMethod method);
template <>
KernelStreams<SphereSoA> sphere_streams<KernelUnit::scalar>(SphereMethod method);
template <>
KernelStreams<SphereSoA> sphere_streams<KernelUnit::scalar_fma>(SphereMethod method);
template <>
KernelStreams<SphereSoA> sphere_streams<KernelUnit::sse4>(SphereMethod method);
template <>
KernelStreams<SphereSoA> sphere_streams<KernelUnit::avx2>(SphereMethod method);
template <>
KernelStreams<SphereSoA> sphere_streams<KernelUnit::avx512>(SphereMethod method);

// Traversal of a BVH over the store, per node width (geometry/bvh_traversal.h).
template <KernelUnit U>
BvhStreams<SphereSoA> sphere_bvh_streams(SphereMethod method);
template <>
BvhStreams<SphereSoA> sphere_bvh_streams<KernelUnit::scalar>(SphereMethod method);
template <>
BvhStreams<SphereSoA> sphere_bvh_streams<KernelUnit::scalar_fma>(SphereMethod method);
template <>
BvhStreams<SphereSoA> sphere_bvh_streams<KernelUnit::sse4>(SphereMethod method);
template <>
BvhStreams<SphereSoA> sphere_bvh_streams<KernelUnit::avx2>(SphereMethod method);
template <>
BvhStreams<SphereSoA> sphere_bvh_streams<KernelUnit::avx512>(SphereMethod method);

}  // namespace quiver
