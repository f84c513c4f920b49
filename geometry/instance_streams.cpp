// Compiled once per kernel unit (simd/kernel_units.h); QUIVER_KERNEL_UNIT names the unit.
#include "geometry/instance_streams.h"

namespace quiver {

template <KernelUnit U>
BvhStreams<InstanceLeaves> instance_bvh_streams() {
  return make_bvh_streams<U, InstanceTopLevel, InstanceLeaves>();
}

// This unit's instances.
template BvhStreams<InstanceLeaves> instance_bvh_streams<kThisUnit>();

}  // namespace quiver
