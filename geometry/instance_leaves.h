// The top level of instancing (geometry/instances.h): a store whose
// primitives are instances, walked by the ordinary BVH walks (packets
// together, or one ray), whose leaf loops carry the leaf's rays into each
// instance's coordinates (o' = W o, d' = W d: t, tmin and tmax unchanged)
// and hand them, the lanes of the leaf only, to the mesh's own BVH streams.
// Closest hit: the (t, id) rule of geometry/leaf_loops.h holds across
// instances, since a mesh's ids shifted by the instance's id_base keep
// their order (the walk inside gets the current id less id_base); a new
// hit's geometric normal goes back to world space by W's transpose. Any
// hit: the lanes still open, within (tmin, tmax). The walks find these
// loops by argument-dependent lookup (the store type is InstanceLeaves).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "geometry/bvh/bvh_streams.h"
#include "geometry/bvh/lane_walk.h"
#include "geometry/instances.h"

namespace quiver {

// The instances a query walks, and what their leaves need: the table, the
// meshes, the mesh streams of the query's unit and method, the tested
// stores (bits, as BvhStores<S, 2>) and the traversal inside instances.
struct InstanceLeaves {
  const InstanceTable* table;
  const InstancedMesh* meshes;
  const BvhStreams<TriangleSoA>* mesh_streams;
  unsigned tested;
  BvhTraversal traversal;

  // An instance's rays walk the top level as one packet (its mesh walk
  // decides for itself how they go inside).
  static constexpr bool kIncoherentRaysTraverseAlone = false;
  std::size_t size() const { return table->size(); }
};

inline namespace QUIVER_UNIT_NAMESPACE {

// The top level's "method": leaves read the world rays as they are.
struct InstanceTopLevel : RayAsIs {};

// One thread's rays and hits of an instance visit (reused: no allocation
// once grown).
struct InstanceVisit {
  RaySoA rays;
  HitSoA hits;
  OcclusionSoA occlusion;
  std::array<int, kMaxLanes> lane{};  // the packet lane of visit ray k
};

inline InstanceVisit& instance_visit() {
  thread_local InstanceVisit visit;
  return visit;
}

// The lanes of `lanes` (bits) of `ray` carried into instance p's
// coordinates, tmax from `tmax`, as visit.rays.
template <class F>
inline void carry_into_instance(const InstanceLeaves& leaves, std::size_t p, const Ray<F>& ray, const F& tmax,
                                unsigned lanes, InstanceVisit& visit) {
  const AffineTransform& to_object = leaves.table->world_to_object[p];
  const Vec3<F> origin = apply_point(to_object, ray.origin);
  const Vec3<F> direction = apply_vector(to_object, ray.direction);
  alignas(64) std::array<float, kMaxLanes> ox, oy, oz, dx, dy, dz, tmin, tend;
  store_lanes(origin.x, ox.data());
  store_lanes(origin.y, oy.data());
  store_lanes(origin.z, oz.data());
  store_lanes(direction.x, dx.data());
  store_lanes(direction.y, dy.data());
  store_lanes(direction.z, dz.data());
  store_lanes(ray.tmin, tmin.data());
  store_lanes(tmax, tend.data());
  visit.rays.clear();
  std::size_t k = 0;
  for (unsigned rest = lanes; rest != 0; rest &= rest - 1, ++k) {
    const int l = __builtin_ctz(rest);
    const std::size_t i = static_cast<std::size_t>(l);
    visit.lane[k] = l;
    visit.rays.push({{ox[i], oy[i], oz[i]}, {dx[i], dy[i], dz[i]}, tmin[i], tend[i]});
  }
  visit.rays.pad();
}

// Calls fn(stores) with the stores of instance p's mesh that the query tests.
template <class Fn>
inline void with_instance_stores(const InstanceLeaves& leaves, std::size_t p, Fn fn) {
  const InstancedMesh& mesh = leaves.meshes[leaves.table->mesh[p]];
  with_tested_stores(mesh.stores[0], mesh.stores[1], leaves.tested, fn);
}

// Closest hits of `lanes` through instances [first, end) (the leaf loop of
// a top-level walk; Test is the walk's, holding the world rays as prepared).
template <class F, class Test>
inline bool closest_one_by_one(const Test& test, const InstanceLeaves& leaves, std::size_t first, std::size_t end,
                               const Mask<F>& lanes, Hit<F>& hit) {
  const Ray<F>& ray = test.prepared;
  const unsigned bits = lane_bits(lanes);
  if (bits == 0) return false;
  InstanceVisit& visit = instance_visit();
  LaneHits<F> lane_hits(hit);
  bool changed = false;
  for (std::size_t p = first; p < end; ++p) {
    const std::int32_t id_base = leaves.table->id_base[p];
    const InstancedMesh& mesh = leaves.meshes[leaves.table->mesh[p]];
    carry_into_instance(leaves, p, ray, lane_hits.packet().t, bits, visit);
    visit.hits.reset(visit.rays);
    for (std::size_t k = 0; k < visit.rays.count; ++k) {
      visit.hits.id[k] = lane_hits.id[static_cast<std::size_t>(visit.lane[k])] - id_base;
    }
    with_instance_stores(leaves, p, [&](auto stores) {
      leaves.mesh_streams->closest_hits(visit.rays, stores, mesh.bvh, visit.hits, leaves.traversal);
    });
    const AffineTransform& to_object = leaves.table->world_to_object[p];
    for (std::size_t k = 0; k < visit.rays.count; ++k) {
      const std::size_t l = static_cast<std::size_t>(visit.lane[k]);
      // No closer hit in this instance: the lane's hit as it came in.
      if (visit.hits.id[k] == lane_hits.id[l] - id_base && visit.hits.t[k] == lane_hits.t[l]) continue;
      Hit<float> h = visit.hits.get(k);
      h.ng = apply_normal(to_object, h.ng);
      h.id += id_base;
      lane_hits.set(l, h);
      changed = true;
    }
  }
  if (changed) hit = lane_hits.packet();
  return changed;
}

// Any hits of the open lanes of `lanes` through instances [first, end):
// the blocked lanes, those blocked on entry included.
template <class F, class Test>
inline Mask<F> occluded_one_by_one(const Test& test, const InstanceLeaves& leaves, std::size_t first,
                                   std::size_t end, const Mask<F>& lanes, const F& tmax, Mask<F> occluded) {
  const Ray<F>& ray = test.prepared;
  InstanceVisit& visit = instance_visit();
  unsigned blocked = lane_bits(occluded);
  for (std::size_t p = first; p < end; ++p) {
    const unsigned open = lane_bits(lanes) & ~blocked;
    if (open == 0) break;
    carry_into_instance(leaves, p, ray, tmax, open, visit);
    visit.occlusion.reset(visit.rays);
    const InstancedMesh& mesh = leaves.meshes[leaves.table->mesh[p]];
    with_instance_stores(leaves, p, [&](auto stores) {
      leaves.mesh_streams->any_hits(visit.rays, stores, mesh.bvh, visit.occlusion, leaves.traversal);
    });
    for (std::size_t k = 0; k < visit.rays.count; ++k) {
      if (visit.occlusion.occluded[k] != 0) blocked |= 1u << visit.lane[k];
    }
  }
  return occluded || mask_from_bits<F>(blocked);
}

}  // namespace QUIVER_UNIT_NAMESPACE
}  // namespace quiver
