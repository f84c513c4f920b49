// The top-level streams of instancing per kernel unit: instance_streams.cpp
// defines them, and each kernel unit compiles it with its own flags.
#pragma once

#include "geometry/bvh/bvh_streams.h"
#include "geometry/instance_leaves.h"

namespace quiver {

// The walks of a BVH of node width kProductNodeWidth over instances
// (geometry/instance_leaves.h).
template <KernelUnit U>
BvhStreams<InstanceLeaves> instance_bvh_streams();

}  // namespace quiver
