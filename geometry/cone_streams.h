// Cone streams per lane width (1, 4, 8), each compiled in its ISA's unit.
#pragma once

#include "geometry/cone_soa.h"
#include "geometry/streams.h"

namespace quiver {

enum class ConeMethod { quadric };

template <int W>
KernelStreams<ConeSoA> cone_streams(ConeMethod method);
template <>
KernelStreams<ConeSoA> cone_streams<1>(ConeMethod method);
template <>
KernelStreams<ConeSoA> cone_streams<4>(ConeMethod method);
template <>
KernelStreams<ConeSoA> cone_streams<8>(ConeMethod method);

}  // namespace quiver
