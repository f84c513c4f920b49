// Polygon streams per lane width (1, 4, 8), each compiled in its ISA's unit.
// Packets only: polygons differ in vertex count, so W polygons cannot share
// one edge loop (no scan orientation).
#pragma once

#include "geometry/polygon_soa.h"
#include "geometry/streams.h"

namespace quiver {

enum class PolygonMethod { crossing };

template <int W>
KernelStreams<PolygonSoA> polygon_streams(PolygonMethod method);
template <>
KernelStreams<PolygonSoA> polygon_streams<1>(PolygonMethod method);
template <>
KernelStreams<PolygonSoA> polygon_streams<4>(PolygonMethod method);
template <>
KernelStreams<PolygonSoA> polygon_streams<8>(PolygonMethod method);

}  // namespace quiver
