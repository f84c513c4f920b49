// Plane streams per kernel unit: plane_streams.cpp defines them, and each kernel
// unit compiles it with its own flags and instantiates them for itself.
#pragma once

#include "geometry/plane_soa.h"
#include "geometry/streams.h"

namespace quiver {

enum class PlaneMethod { seed };

template <KernelUnit U>
KernelStreams<PlaneSoA> plane_streams(PlaneMethod method);

}  // namespace quiver
