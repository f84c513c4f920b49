// Triangle streams per lane width (1, 4, 8), each compiled in its ISA's unit.
#pragma once

#include "geometry/streams.h"
#include "geometry/triangle_soa.h"

namespace quiver {

enum class TriangleMethod { moller_trumbore, watertight };

template <int W>
KernelStreams<TriangleSoA> triangle_streams(TriangleMethod method);
template <>
KernelStreams<TriangleSoA> triangle_streams<1>(TriangleMethod method);
template <>
KernelStreams<TriangleSoA> triangle_streams<4>(TriangleMethod method);
template <>
KernelStreams<TriangleSoA> triangle_streams<8>(TriangleMethod method);

}  // namespace quiver
