// The scene's intersection queries for one kernel unit: each layer's stores
// in turn, through the store's BVH where it has one (geometry/bvh_traversal.h)
// and otherwise through the packet streams (W rays against one primitive),
// with the robust sphere, watertight triangle, crossing polygon, seed plane
// and quadric cone methods. HitSoA carries the closest t, so the stores
// compose; every path reports the smallest (t, id), so the order does not
// matter.
#pragma once

#include "geometry/cone_streams.h"
#include "geometry/plane_streams.h"
#include "geometry/polygon_streams.h"
#include "geometry/sphere_streams.h"
#include "geometry/triangle_streams.h"
#include "integrator/scene.h"

namespace quiver {

class SceneIntersector {
 public:
  explicit SceneIntersector(KernelUnit unit);

  KernelUnit unit() const { return unit_; }
  // How packets walk the BVHs (automatic: together when coherent).
  void set_traversal(BvhTraversal traversal) { traversal_ = traversal; }
  int lanes() const { return lane_width(unit_); }

  // Closest hits of both layers (hits.t starts as each ray's tmax).
  void closest(const Scene& scene, const RaySoA& rays, HitSoA& hits) const;
  // Closest hits of one layer.
  void closest(const GeometryLayer& layer, const RaySoA& rays, HitSoA& hits) const;
  // Any hit of one layer within (tmin, tmax).
  void occluded(const GeometryLayer& layer, const RaySoA& rays, OcclusionSoA& result) const;

 private:
  KernelUnit unit_;
  BvhTraversal traversal_ = BvhTraversal::automatic;
  BvhStreams<SphereSoA> sphere_bvh_;
  BvhStreams<TriangleSoA> triangle_bvh_;
  BvhStreams<PolygonSoA> polygon_bvh_;
  BvhStreams<ConeSoA> cone_bvh_;
  KernelStreams<SphereSoA> spheres_;
  KernelStreams<PlaneSoA> planes_;
  KernelStreams<TriangleSoA> triangles_;
  KernelStreams<PolygonSoA> polygons_;
  KernelStreams<ConeSoA> cones_;
};

}  // namespace quiver
