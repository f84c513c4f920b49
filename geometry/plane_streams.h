// Plane streams per kernel unit: plane_streams.cpp defines them, and each kernel
// unit compiles it with its own flags and instantiates them for itself.
#pragma once

#include "geometry/plane_soa.h"
#include "geometry/streams.h"

namespace quiver {

// seed: t from the offset d; anchored: t from the plane's point (geometry/plane.h).
enum class PlaneMethod { seed, anchored };

// The product's method, anchored, as packets (seed:
// tests/support/study_streams.h; the product's function throws
// std::invalid_argument for it).
template <KernelUnit U>
KernelStreams<PlaneSoA> plane_streams(PlaneMethod method);

}  // namespace quiver
