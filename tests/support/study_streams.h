// The study's streams: every method of every kind, in both orientations
// (packets and, where a kind has it, scan), and BVH walks of node widths 2,
// 4 and 8, for the tests, benchmarks and accuracy study that compare them.
// The product (geometry/kind_streams.h) builds only what quiver runs;
// these return the product's own function pointers where they coincide.
// Non-product methods walk BVHs of kProductNodeWidth only.
#pragma once

#include "geometry/kind_streams.h"
#include "geometry/instance_streams.h"
#include "integrator/scene_intersector.h"

namespace quiver {

template <KernelUnit U>
KernelStreams<SphereSoA> study_sphere_streams(SphereMethod method);
template <KernelUnit U>
BvhStreams<SphereSoA> study_sphere_bvh_streams(SphereMethod method);

template <KernelUnit U>
KernelStreams<PlaneSoA> study_plane_streams(PlaneMethod method);

template <KernelUnit U>
KernelStreams<TriangleSoA> study_triangle_streams(TriangleMethod method);
template <KernelUnit U>
BvhStreams<TriangleSoA> study_triangle_bvh_streams(TriangleMethod method);

template <KernelUnit U>
KernelStreams<PolygonSoA> study_polygon_streams(PolygonMethod method);
template <KernelUnit U>
BvhStreams<PolygonSoA> study_polygon_bvh_streams(PolygonMethod method);

template <KernelUnit U>
KernelStreams<ConeSoA> study_cone_streams(ConeMethod method);
template <KernelUnit U>
BvhStreams<ConeSoA> study_cone_bvh_streams(ConeMethod method);

template <KernelUnit U>
BvhStreams<InstanceLeaves> study_instance_bvh_streams();

// The product's scene streams (integrator/scene_intersector.h) with BVH
// walks of every node width, for scenes built with any width.
SceneStreams study_scene_streams(KernelUnit unit, SphereMethod sphere);

// The node widths a study BVH stream walks.
inline constexpr int kStudyNodeWidths[] = {2, 4, 8};

inline namespace QUIVER_UNIT_NAMESPACE {

// A product BVH stream of Method with node widths 2 and 4 added.
template <KernelUnit U, class Method, class S>
BvhStreams<S> with_study_widths(BvhStreams<S> s) {
  add_bvh_width<U, Method, S, 2>(s);
  add_bvh_width<U, Method, S, 4>(s);
  return s;
}

}  // namespace QUIVER_UNIT_NAMESPACE

}  // namespace quiver
