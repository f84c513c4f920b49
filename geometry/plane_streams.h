// Plane streams per kernel unit (simd/isa.h), each compiled with that unit's flags.
#pragma once

#include "geometry/plane_soa.h"
#include "geometry/streams.h"

namespace quiver {

enum class PlaneMethod { seed };

template <KernelUnit U>
KernelStreams<PlaneSoA> plane_streams(PlaneMethod method);
template <>
KernelStreams<PlaneSoA> plane_streams<KernelUnit::scalar>(PlaneMethod method);
template <>
KernelStreams<PlaneSoA> plane_streams<KernelUnit::scalar_fma>(PlaneMethod method);
template <>
KernelStreams<PlaneSoA> plane_streams<KernelUnit::sse4>(PlaneMethod method);
template <>
KernelStreams<PlaneSoA> plane_streams<KernelUnit::avx2>(PlaneMethod method);
template <>
KernelStreams<PlaneSoA> plane_streams<KernelUnit::avx512>(PlaneMethod method);

}  // namespace quiver
