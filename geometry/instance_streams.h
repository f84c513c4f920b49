// The top-level streams of instancing per kernel unit: instance_streams.cpp
// defines them, and each kernel unit compiles it with its own flags.
#pragma once

#include "geometry/bvh/bvh_streams.h"
#include "geometry/instance_leaves.h"

namespace quiver {

// The walks of a BVH over instances (geometry/instance_leaves.h), per node
// width, through a tree over one store.
template <KernelUnit U>
BvhStreams<InstanceLeaves> instance_bvh_streams();

}  // namespace quiver
