// Polygon streams per kernel unit: polygon_streams.cpp defines them, and each kernel
// unit compiles it with its own flags and instantiates them for itself.
// Packets only: polygons differ in vertex count, so W polygons cannot share
// one edge loop (no scan orientation).
#pragma once

#include "geometry/bvh/bvh_streams.h"
#include "geometry/polygon_soa.h"
#include "geometry/streams.h"

namespace quiver {

enum class PolygonMethod { crossing };

template <KernelUnit U>
KernelStreams<PolygonSoA> polygon_streams(PolygonMethod method);

// Traversal of a BVH of node width kProductNodeWidth over the store
// (geometry/bvh/bvh_streams.h).
template <KernelUnit U>
BvhStreams<PolygonSoA> polygon_bvh_streams(PolygonMethod method);

}  // namespace quiver
