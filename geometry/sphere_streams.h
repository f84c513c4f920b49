// Sphere streams per kernel unit: sphere_streams.cpp defines them, and each kernel
// unit compiles it with its own flags and instantiates them for itself.
#pragma once

#include "geometry/bvh/bvh_streams.h"
#include "geometry/sphere_soa.h"
#include "geometry/streams.h"

namespace quiver {

enum class SphereMethod { algebraic, geometric, robust };

// The product's methods, algebraic and robust, as packets (geometric:
// tests/support/study_streams.h; the product's functions throw
// std::invalid_argument for it).
template <KernelUnit U>
KernelStreams<SphereSoA> sphere_streams(SphereMethod method);

// Traversal of a BVH of node width kProductNodeWidth over the store
// (geometry/bvh/bvh_streams.h).
template <KernelUnit U>
BvhStreams<SphereSoA> sphere_bvh_streams(SphereMethod method);

}  // namespace quiver
