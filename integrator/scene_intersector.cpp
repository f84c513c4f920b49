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
  const SphereSoA& opaque = scene.opaque.store<SphereKind>();
  const SphereSoA& transmissive = scene.transmissive.store<SphereKind>();
  if (opaque.count + transmissive.count == 0) return 0.0;
  if (scene.opaque.store<PlaneKind>().count + scene.transmissive.store<PlaneKind>().count > 0) {
    return std::numeric_limits<double>::infinity();
  }
  double lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    const double eye = scene.camera.from[a];
    lo[a] = std::min(double(scene.bounds_min[a]), eye);
    hi[a] = std::max(double(scene.bounds_max[a]), eye);
  }
  return std::sqrt(std::max(max_squared_ratio(opaque, lo, hi), max_squared_ratio(transmissive, lo, hi)));
}

SphereMethod choose_sphere_method(const Scene& scene, MethodChoice choice) {
  const bool has_spheres = scene.opaque.store<SphereKind>().count + scene.transmissive.store<SphereKind>().count > 0;
  const bool safe = sphere_origin_distance_ratio(scene) <= kAlgebraicSphereMaxDistanceRatio;
  return choice == MethodChoice::per_scene && has_spheres && safe ? SphereMethod::algebraic : SphereMethod::robust;
}

SceneStreams product_scene_streams(KernelUnit unit, SphereMethod sphere) {
  KindMethods methods;
  methods.of<SphereKind>().method = sphere;
  return with_kernel_unit(unit, [&](auto u) {
    constexpr KernelUnit U = decltype(u)::value;
    return SceneStreams{product_kind_streams<U>(methods), instance_bvh_streams<U>()};
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

// One kind's stores in both layers, its BVH and its streams.
template <class K>
struct KindQuery {
  using Store = typename K::Store;
  const KindStore<K>& opaque;
  const KindStore<K>& transmissive;
  const Bvh& bvh;
  const KindStreams<K>& streams;

  bool has(Layers layers, bool transmissive_layer) const {
    return tests(layers, transmissive_layer) && (transmissive_layer ? transmissive : opaque).store.count > 0;
  }
  // Without a BVH, scan(store, box) for each tested layer's store, box its
  // bounds for a bounded kind (the packets that pass it by skip the store),
  // else nullptr. With one, through_tree(stores): both stores when both
  // layers have this kind (the tree's leaves of untested layers are
  // skipped), else the one store there is, when its layer is tested.
  template <class ThroughTree, class Scan>
  void visit(Layers layers, ThroughTree through_tree, Scan scan) const {
    if (bvh.empty()) {
      for (const KindStore<K>* k : {&opaque, &transmissive}) {
        if (has(layers, k == &transmissive)) scan(k->store, K::bounded ? &k->bounds : nullptr);
      }
    } else {
      with_tested_stores(opaque.store, transmissive.store, static_cast<unsigned>(layers), through_tree);
    }
  }
};

// fn(KindQuery) for each kind, the unbounded (always scanned) first: their
// hits shorten every walk that follows.
template <class Fn>
void for_each_kind_query(const Scene& scene, const ProductStreams& streams, Fn fn) {
  const auto query = [&]<class K>(K) {
    fn(KindQuery<K>{scene.opaque.kinds.of<K>(), scene.transmissive.kinds.of<K>(), scene.bvh<K>(), streams.of<K>()});
  };
  for_each_kind([&]<class K>(K k) {
    if constexpr (!K::bounded) query(k);
  });
  for_each_kind([&]<class K>(K k) {
    if constexpr (K::bounded) query(k);
  });
}

}  // namespace

InstanceLeaves SceneIntersector::instance_leaves(const Scene& scene, Layers layers) const {
  return {&scene.instances, scene.meshes.data(), &streams_.kinds.of<TriangleKind>().tree, static_cast<unsigned>(layers), traversal_};
}

void SceneIntersector::closest(const Scene& scene, const RaySoA& rays, HitSoA& hits, Layers layers) const {
  if (rays.count == 0) return;
  for_each_kind_query(scene, streams_.kinds, [&](const auto& kind) {
    kind.visit(
        layers, [&](const auto& stores) { kind.streams.tree.closest_hits(rays, stores, kind.bvh, hits, traversal_); },
        [&](const auto& store, const Box* box) {
          box != nullptr ? kind.streams.scan.closest_packets_within(rays, store, *box, hits)
                         : kind.streams.scan.closest_packets(rays, store, hits);
        });
  });
  if (!scene.instance_bvh.empty()) {
    streams_.instance_bvh.closest_hits(rays, instance_leaves(scene, layers), scene.instance_bvh, hits, traversal_);
  }
}

void SceneIntersector::occluded(const Scene& scene, const RaySoA& rays, OcclusionSoA& result, Layers layers) const {
  if (rays.count == 0) return;
  for_each_kind_query(scene, streams_.kinds, [&](const auto& kind) {
    kind.visit(
        layers, [&](const auto& stores) { kind.streams.tree.any_hits(rays, stores, kind.bvh, result, traversal_); },
        [&](const auto& store, const Box* box) {
          box != nullptr ? kind.streams.scan.occluded_packets_within(rays, store, *box, result)
                         : kind.streams.scan.occluded_packets(rays, store, result);
        });
  });
  if (!scene.instance_bvh.empty()) {
    streams_.instance_bvh.any_hits(rays, instance_leaves(scene, layers), scene.instance_bvh, result, traversal_);
  }
}

}  // namespace quiver
