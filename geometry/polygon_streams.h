// Polygon streams per kernel unit (simd/isa.h), each compiled with that unit's flags.
// Packets only: polygons differ in vertex count, so W polygons cannot share
// one edge loop (no scan orientation).
#pragma once

#include "geometry/bvh_traversal.h"
#include "geometry/polygon_soa.h"
#include "geometry/streams.h"

namespace quiver {

enum class PolygonMethod { crossing };

template <KernelUnit U>
KernelStreams<PolygonSoA> polygon_streams(PolygonMethod method);
template <>
KernelStreams<PolygonSoA> polygon_streams<KernelUnit::scalar>(PolygonMethod method);
template <>
KernelStreams<PolygonSoA> polygon_streams<KernelUnit::scalar_fma>(PolygonMethod method);
template <>
KernelStreams<PolygonSoA> polygon_streams<KernelUnit::sse4>(PolygonMethod method);
template <>
KernelStreams<PolygonSoA> polygon_streams<KernelUnit::avx2>(PolygonMethod method);
template <>
KernelStreams<PolygonSoA> polygon_streams<KernelUnit::avx512>(PolygonMethod method);

// Traversal of a BVH over the store, per node width (geometry/bvh_traversal.h).
template <KernelUnit U>
BvhStreams<PolygonSoA> polygon_bvh_streams(PolygonMethod method);
template <>
BvhStreams<PolygonSoA> polygon_bvh_streams<KernelUnit::scalar>(PolygonMethod method);
template <>
BvhStreams<PolygonSoA> polygon_bvh_streams<KernelUnit::scalar_fma>(PolygonMethod method);
template <>
BvhStreams<PolygonSoA> polygon_bvh_streams<KernelUnit::sse4>(PolygonMethod method);
template <>
BvhStreams<PolygonSoA> polygon_bvh_streams<KernelUnit::avx2>(PolygonMethod method);
template <>
BvhStreams<PolygonSoA> polygon_bvh_streams<KernelUnit::avx512>(PolygonMethod method);

}  // namespace quiver
