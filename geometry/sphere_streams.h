// Sphere streams per lane width (1, 4, 8), each compiled in its ISA's unit.
#pragma once

#include "geometry/sphere_soa.h"
#include "geometry/streams.h"

namespace quiver {

enum class SphereMethod { algebraic, geometric, robust };

template <int W>
KernelStreams<SphereSoA> sphere_streams(SphereMethod method);
template <>
KernelStreams<SphereSoA> sphere_streams<1>(SphereMethod method);
template <>
KernelStreams<SphereSoA> sphere_streams<4>(SphereMethod method);
template <>
KernelStreams<SphereSoA> sphere_streams<8>(SphereMethod method);

}  // namespace quiver
