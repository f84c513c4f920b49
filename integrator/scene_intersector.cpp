#include "integrator/scene_intersector.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

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

SceneStreams product_scene_streams(KernelUnit unit, SphereMethod sphere) {
  return with_kernel_unit(unit, [sphere](auto u) {
    constexpr KernelUnit U = decltype(u)::value;
    SceneStreams s;
    s.spheres = sphere_streams<U>(sphere);
    s.planes = plane_streams<U>(PlaneMethod::anchored);
    s.triangles = triangle_streams<U>(TriangleMethod::watertight);
    s.polygons = polygon_streams<U>(PolygonMethod::crossing);
    s.cones = cone_streams<U>(ConeMethod::quadric);
    s.sphere_bvh = sphere_bvh_streams<U>(sphere);
    s.triangle_bvh = triangle_bvh_streams<U>(TriangleMethod::watertight);
    s.polygon_bvh = polygon_bvh_streams<U>(PolygonMethod::crossing);
    s.cone_bvh = cone_bvh_streams<U>(ConeMethod::quadric);
    s.instance_bvh = instance_bvh_streams<U>();
    return s;
  });
}

SceneIntersector::SceneIntersector(KernelUnit unit, SphereMethod sphere)
    : SceneIntersector(unit, sphere, product_scene_streams(unit, sphere)) {}

SceneIntersector::SceneIntersector(KernelUnit unit, SphereMethod sphere, SceneStreams streams)
    : unit_(unit), sphere_method_(sphere), streams_(std::move(streams)) {}

namespace {

bool tests(Layers layers, bool transmissive) {
  return (static_cast<unsigned>(layers) >> (transmissive ? 1 : 0) & 1u) != 0;
}

// Calls fn with the plane store of each tested layer that has planes.
template <class Fn>
void for_each_tested_plane_store(const Scene& scene, Layers layers, Fn fn) {
  for (bool transmissive : {false, true}) {
    const PlaneSoA& planes = scene.layer(transmissive).planes;
    if (tests(layers, transmissive) && planes.count > 0) fn(planes);
  }
}

// One bounded kind's stores in both layers, its BVH and its streams.
template <class S>
struct KindQuery {
  const S& opaque;
  const S& transmissive;
  const Bvh& bvh;
  const KernelStreams<S>& scan;
  const BvhStreams<S>& tree;

  bool has(Layers layers, bool transmissive_layer) const {
    return tests(layers, transmissive_layer) && (transmissive_layer ? transmissive : opaque).count > 0;
  }
  // Without a BVH, scan(store) for each tested layer's store. With one,
  // through_tree(stores): both stores when both layers have this kind (the
  // tree's leaves of untested layers are skipped), else the one store there
  // is, when its layer is tested.
  template <class ThroughTree, class Scan>
  void visit(Layers layers, ThroughTree through_tree, Scan scan_store) const {
    if (bvh.empty()) {
      if (has(layers, false)) scan_store(opaque);
      if (has(layers, true)) scan_store(transmissive);
    } else {
      with_tested_stores(opaque, transmissive, static_cast<unsigned>(layers), through_tree);
    }
  }
};

template <class S>
KindQuery<S> kind_query(const S& opaque, const S& transmissive, const Bvh& bvh, const KernelStreams<S>& scan,
                        const BvhStreams<S>& tree) {
  return {opaque, transmissive, bvh, scan, tree};
}

}  // namespace

template <class Fn>
void SceneIntersector::for_each_bounded_kind(const Scene& scene, Fn fn) const {
  const GeometryLayer& o = scene.opaque;
  const GeometryLayer& t = scene.transmissive;
  fn(kind_query(o.spheres, t.spheres, scene.sphere_bvh, streams_.spheres, streams_.sphere_bvh));
  fn(kind_query(o.triangles, t.triangles, scene.triangle_bvh, streams_.triangles, streams_.triangle_bvh));
  fn(kind_query(o.polygons, t.polygons, scene.polygon_bvh, streams_.polygons, streams_.polygon_bvh));
  fn(kind_query(o.cones, t.cones, scene.cone_bvh, streams_.cones, streams_.cone_bvh));
}

InstanceLeaves SceneIntersector::instance_leaves(const Scene& scene, Layers layers) const {
  return {&scene.instances, scene.meshes.data(), &streams_.triangle_bvh, static_cast<unsigned>(layers), traversal_};
}

void SceneIntersector::closest(const Scene& scene, const RaySoA& rays, HitSoA& hits, Layers layers) const {
  if (rays.count == 0) return;
  for_each_tested_plane_store(scene, layers,
                              [&](const PlaneSoA& planes) { streams_.planes.closest_packets(rays, planes, hits); });
  for_each_bounded_kind(scene, [&](const auto& kind) {
    kind.visit(
        layers, [&](const auto& stores) { kind.tree.closest_hits(rays, stores, kind.bvh, hits, traversal_); },
        [&](const auto& store) { kind.scan.closest_packets(rays, store, hits); });
  });
  if (!scene.instance_bvh.empty()) {
    streams_.instance_bvh.closest_hits(rays, instance_leaves(scene, layers), scene.instance_bvh, hits, traversal_);
  }
}

void SceneIntersector::occluded(const Scene& scene, const RaySoA& rays, OcclusionSoA& result, Layers layers) const {
  if (rays.count == 0) return;
  for_each_tested_plane_store(scene, layers,
                              [&](const PlaneSoA& planes) { streams_.planes.occluded_packets(rays, planes, result); });
  for_each_bounded_kind(scene, [&](const auto& kind) {
    kind.visit(
        layers, [&](const auto& stores) { kind.tree.any_hits(rays, stores, kind.bvh, result, traversal_); },
        [&](const auto& store) { kind.scan.occluded_packets(rays, store, result); });
  });
  if (!scene.instance_bvh.empty()) {
    streams_.instance_bvh.any_hits(rays, instance_leaves(scene, layers), scene.instance_bvh, result, traversal_);
  }
}

}  // namespace quiver
