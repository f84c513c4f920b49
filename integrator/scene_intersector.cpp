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
    sphere_bvh_ = sphere_bvh_streams<U>(SphereMethod::robust);
    triangle_bvh_ = triangle_bvh_streams<U>(TriangleMethod::watertight);
    polygon_bvh_ = polygon_bvh_streams<U>(PolygonMethod::crossing);
    cone_bvh_ = cone_bvh_streams<U>(ConeMethod::quadric);
  });
}

void SceneIntersector::closest(const Scene& scene, const RaySoA& rays, HitSoA& hits) const {
  closest(scene.opaque, rays, hits);
  closest(scene.transmissive, rays, hits);
}

void SceneIntersector::closest(const GeometryLayer& g, const RaySoA& rays, HitSoA& hits) const {
  if (rays.count == 0) return;
  auto each = [&](const auto& store, const Bvh& bvh, const auto& scan, const auto& tree) {
    if (store.count == 0) return;
    if (bvh.empty()) {
      scan.closest_packets(rays, store, hits);
    } else {
      tree.closest_hits(rays, store, bvh, hits, traversal_);
    }
  };
  each(g.spheres, g.sphere_bvh, spheres_, sphere_bvh_);
  if (g.planes.count > 0) planes_.closest_packets(rays, g.planes, hits);
  each(g.triangles, g.triangle_bvh, triangles_, triangle_bvh_);
  each(g.polygons, g.polygon_bvh, polygons_, polygon_bvh_);
  each(g.cones, g.cone_bvh, cones_, cone_bvh_);
}

void SceneIntersector::occluded(const GeometryLayer& g, const RaySoA& rays, OcclusionSoA& result) const {
  if (rays.count == 0) return;
  auto each = [&](const auto& store, const Bvh& bvh, const auto& scan, const auto& tree) {
    if (store.count == 0) return;
    if (bvh.empty()) {
      scan.occluded_packets(rays, store, result);
    } else {
      tree.any_hits(rays, store, bvh, result, traversal_);
    }
  };
  if (g.planes.count > 0) planes_.occluded_packets(rays, g.planes, result);
  each(g.spheres, g.sphere_bvh, spheres_, sphere_bvh_);
  each(g.triangles, g.triangle_bvh, triangles_, triangle_bvh_);
  each(g.polygons, g.polygon_bvh, polygons_, polygon_bvh_);
  each(g.cones, g.cone_bvh, cones_, cone_bvh_);
}

}  // namespace quiver
