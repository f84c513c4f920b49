// Cone streams per kernel unit (simd/isa.h), each compiled with that unit's flags.
#pragma once

#include "geometry/cone_soa.h"
#include "geometry/streams.h"

namespace quiver {

enum class ConeMethod { quadric };

template <KernelUnit U>
KernelStreams<ConeSoA> cone_streams(ConeMethod method);
template <>
KernelStreams<ConeSoA> cone_streams<KernelUnit::scalar>(ConeMethod method);
template <>
KernelStreams<ConeSoA> cone_streams<KernelUnit::scalar_fma>(ConeMethod method);
template <>
KernelStreams<ConeSoA> cone_streams<KernelUnit::sse4>(ConeMethod method);
template <>
KernelStreams<ConeSoA> cone_streams<KernelUnit::avx2>(ConeMethod method);

}  // namespace quiver
