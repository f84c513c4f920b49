// Triangle streams per kernel unit: triangle_streams.cpp defines them, and each kernel
// unit compiles it with its own flags and instantiates them for itself.
#pragma once

#include "geometry/bvh/bvh_streams.h"
#include "geometry/streams.h"
#include "geometry/triangle_soa.h"

namespace quiver {

enum class TriangleMethod { moller_trumbore, watertight };

// The product's method, watertight, as packets (moller_trumbore:
// tests/support/study_streams.h; the product's functions throw
// std::invalid_argument for it).
template <KernelUnit U>
KernelStreams<TriangleSoA> triangle_streams(TriangleMethod method);

// Traversal of a BVH of node width kProductNodeWidth over the store
// (geometry/bvh/bvh_streams.h).
template <KernelUnit U>
BvhStreams<TriangleSoA> triangle_bvh_streams(TriangleMethod method);

}  // namespace quiver
