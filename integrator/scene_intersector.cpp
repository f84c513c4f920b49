#include "integrator/scene_intersector.h"

namespace quiver {

SceneIntersector::SceneIntersector(KernelUnit unit) : unit_(unit) {
  with_kernel_unit(unit, [this](auto u) {
    constexpr KernelUnit U = decltype(u)::value;
    spheres_ = sphere_streams<U>(SphereMethod::robust);
    planes_ = plane_streams<U>(PlaneMethod::seed);
    triangles_ = triangle_streams<U>(TriangleMethod::watertight);
    polygons_ = polygon_streams<U>(PolygonMethod::crossing);
    cones_ = cone_streams<U>(ConeMethod::quadric);
  });
}

void SceneIntersector::closest(const Scene& scene, const RaySoA& rays, HitSoA& hits) const {
  closest(scene.opaque, rays, hits);
  closest(scene.transmissive, rays, hits);
}

void SceneIntersector::closest(const GeometryLayer& g, const RaySoA& rays, HitSoA& hits) const {
  if (rays.count == 0) return;
  if (g.spheres.count > 0) spheres_.closest_packets(rays, g.spheres, hits);
  if (g.planes.count > 0) planes_.closest_packets(rays, g.planes, hits);
  if (g.triangles.count > 0) triangles_.closest_packets(rays, g.triangles, hits);
  if (g.polygons.count > 0) polygons_.closest_packets(rays, g.polygons, hits);
  if (g.cones.count > 0) cones_.closest_packets(rays, g.cones, hits);
}

void SceneIntersector::occluded(const GeometryLayer& g, const RaySoA& rays, OcclusionSoA& result) const {
  if (rays.count == 0) return;
  if (g.spheres.count > 0) spheres_.occluded_packets(rays, g.spheres, result);
  if (g.planes.count > 0) planes_.occluded_packets(rays, g.planes, result);
  if (g.triangles.count > 0) triangles_.occluded_packets(rays, g.triangles, result);
  if (g.polygons.count > 0) polygons_.occluded_packets(rays, g.polygons, result);
  if (g.cones.count > 0) cones_.occluded_packets(rays, g.cones, result);
}

}  // namespace quiver
