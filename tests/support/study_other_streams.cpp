// Compiled once per kernel unit (simd/kernel_units.h), like the product's
// kernels: the study's planes, polygons, cones and instances, whose methods
// are the product's (but for the seed plane), at every node width.
#include "tests/support/study_streams.h"

namespace quiver {

template <KernelUnit U>
KernelStreams<PlaneSoA> study_plane_streams(PlaneMethod method) {
  switch (method) {
    case PlaneMethod::seed: return make_streams<U, PlaneSeed, PlaneSoA>();
    case PlaneMethod::anchored: break;
  }
  return make_streams<U, PlaneAnchored, PlaneSoA>();
}

template <KernelUnit U>
KernelStreams<PolygonSoA> study_polygon_streams(PolygonMethod method) {
  return product_streams_of<U, PolygonKind>(method).scan;  // packets only: no scan orientation
}

template <KernelUnit U>
BvhStreams<PolygonSoA> study_polygon_bvh_streams(PolygonMethod method) {
  return with_study_widths<U, PolygonCrossing>(product_streams_of<U, PolygonKind>(method).tree);
}

template <KernelUnit U>
KernelStreams<ConeSoA> study_cone_streams(ConeMethod method) {
  switch (method) {
    case ConeMethod::quadric: break;
  }
  return make_streams<U, ConeQuadric, ConeSoA>();
}

template <KernelUnit U>
BvhStreams<ConeSoA> study_cone_bvh_streams(ConeMethod method) {
  return with_study_widths<U, ConeQuadric>(product_streams_of<U, ConeKind>(method).tree);
}

template <KernelUnit U>
BvhStreams<InstanceLeaves> study_instance_bvh_streams() {
  return with_study_widths<U, InstanceTopLevel>(instance_bvh_streams<U>());
}

template KernelStreams<PlaneSoA> study_plane_streams<kThisUnit>(PlaneMethod);
template KernelStreams<PolygonSoA> study_polygon_streams<kThisUnit>(PolygonMethod);
template BvhStreams<PolygonSoA> study_polygon_bvh_streams<kThisUnit>(PolygonMethod);
template KernelStreams<ConeSoA> study_cone_streams<kThisUnit>(ConeMethod);
template BvhStreams<ConeSoA> study_cone_bvh_streams<kThisUnit>(ConeMethod);
template BvhStreams<InstanceLeaves> study_instance_bvh_streams<kThisUnit>();

}  // namespace quiver
