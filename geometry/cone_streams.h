// Cone streams per kernel unit: cone_streams.cpp defines them, and each kernel
// unit compiles it with its own flags and instantiates them for itself.
#pragma once

#include "geometry/bvh/bvh_streams.h"
#include "geometry/cone_soa.h"
#include "geometry/streams.h"

namespace quiver {

enum class ConeMethod { quadric };

template <KernelUnit U>
KernelStreams<ConeSoA> cone_streams(ConeMethod method);

// Traversal of a BVH of node width kProductNodeWidth over the store
// (geometry/bvh/bvh_streams.h).
template <KernelUnit U>
BvhStreams<ConeSoA> cone_bvh_streams(ConeMethod method);

}  // namespace quiver
