#include "integrator/scene_intersector.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace quiver {

namespace {

// max over spheres of |farthest point of [lo, hi] from the centre|^2 / r^2, in double.
double max_squared_ratio(const SphereSoA& spheres, const double lo[3], const double hi[3]) {
  double worst = 0.0;
  for (std::size_t i = 0; i < spheres.count; ++i) {
    const double center[3] = {spheres.cx[i], spheres.cy[i], spheres.cz[i]};
    double squared = 0.0;
    for (int a = 0; a < 3; ++a) {
      const double reach = std::max(center[a] - lo[a], hi[a] - center[a]);
      squared += reach * reach;
    }
    worst = std::max(worst, squared / double(spheres.r2[i]));
  }
  return worst;
}

}  // namespace

double sphere_origin_distance_ratio(const Scene& scene) {
  if (scene.opaque.spheres.count + scene.transmissive.spheres.count == 0) return 0.0;
  if (scene.opaque.planes.count + scene.transmissive.planes.count > 0) return std::numeric_limits<double>::infinity();
  double lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    const double eye = scene.camera.from[a];
    lo[a] = std::min(double(scene.bounds_min[a]), eye);
    hi[a] = std::max(double(scene.bounds_max[a]), eye);
  }
  return std::sqrt(std::max(max_squared_ratio(scene.opaque.spheres, lo, hi),
                            max_squared_ratio(scene.transmissive.spheres, lo, hi)));
}

SphereMethod choose_sphere_method(const Scene& scene, MethodChoice choice) {
  const bool has_spheres = scene.opaque.spheres.count + scene.transmissive.spheres.count > 0;
  const bool safe = sphere_origin_distance_ratio(scene) <= kAlgebraicSphereMaxDistanceRatio;
  return choice == MethodChoice::per_scene && has_spheres && safe ? SphereMethod::algebraic : SphereMethod::robust;
}

SceneIntersector::SceneIntersector(KernelUnit unit, SphereMethod sphere) : unit_(unit), sphere_method_(sphere) {
  with_kernel_unit(unit, [this](auto u) {
    constexpr KernelUnit U = decltype(u)::value;
    spheres_ = sphere_streams<U>(sphere_method_);
    planes_ = plane_streams<U>(PlaneMethod::seed);
    triangles_ = triangle_streams<U>(TriangleMethod::watertight);
    polygons_ = polygon_streams<U>(PolygonMethod::crossing);
    cones_ = cone_streams<U>(ConeMethod::quadric);
    sphere_bvh_ = sphere_bvh_streams<U>(sphere_method_);
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
