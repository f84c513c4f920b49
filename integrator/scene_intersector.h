// The scene's intersection queries for one kernel unit: each layer's stores
// in turn through their packet streams (W rays against one primitive), the
// robust sphere, watertight triangle, crossing polygon, seed plane and
// quadric cone methods. HitSoA carries the closest t, so the stores compose.
// Until the BVH lands this scans every primitive; the interface stays.
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
  int lanes() const { return lane_width(unit_); }

  // Closest hits of both layers (hits.t starts as each ray's tmax).
  void closest(const Scene& scene, const RaySoA& rays, HitSoA& hits) const;
  // Closest hits of one layer.
  void closest(const GeometryLayer& layer, const RaySoA& rays, HitSoA& hits) const;
  // Any hit of one layer within (tmin, tmax).
  void occluded(const GeometryLayer& layer, const RaySoA& rays, OcclusionSoA& result) const;

 private:
  KernelUnit unit_;
  KernelStreams<SphereSoA> spheres_;
  KernelStreams<PlaneSoA> planes_;
  KernelStreams<TriangleSoA> triangles_;
  KernelStreams<PolygonSoA> polygons_;
  KernelStreams<ConeSoA> cones_;
};

}  // namespace quiver
