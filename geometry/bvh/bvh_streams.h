// BVH traversal streams through one primitive store, or through the tested
// stores of a tree over two (a scene's opaque and transmissive layers,
// BvhStores), written once for every width. Per packet the stream decides:
// packets travel together (geometry/bvh/packet_walk.h), except that
// triangle packets whose active lanes' directions span several octants
// (incoherent) go ray by ray (geometry/bvh/lane_walk.h,
// geometry/bvh/single_walk.h), after one packet test of the root's children
// answers the lanes that enter none; rays reaching behind their origin
// always walk alone. The closest hit is the lexicographic minimum of (t, id) over
// the stores, as a brute-force scan in id order gives it, so the result
// does not depend on traversal order, packet or single, or width.
#pragma once

#include <array>
#include <cstddef>

#include "geometry/bvh.h"
#include "geometry/bvh/lane_walk.h"
#include "geometry/bvh/packet_walk.h"
#include "geometry/bvh/single_walk.h"
#include "geometry/streams.h"

namespace quiver {

// Thrown by a BVH stream asked to walk a node width it lacks:
// std::invalid_argument naming it. Out of line (geometry/streams.cpp), so no
// kernel unit's flags compile the library code it calls.
[[noreturn]] void throw_missing_node_width(int width);

// The BVH streams of one method per node width (2, 4, 8), through a tree
// over one store or through the tested stores of a tree over two. The
// product fills width kProductNodeWidth only; a walk asked of a width
// left empty throws std::invalid_argument.
template <class S>
struct BvhStreams {
  template <int K>
  using Closest = void (*)(const RaySoA&, BvhStores<S, K>, const Bvh&, HitSoA&, BvhTraversal);
  template <int K>
  using Occluded = void (*)(const RaySoA&, BvhStores<S, K>, const Bvh&, OcclusionSoA&, BvhTraversal);
  std::array<Closest<1>, 3> closest{};
  std::array<Occluded<1>, 3> occluded{};
  std::array<Closest<2>, 3> closest_of_two{};
  std::array<Occluded<2>, 3> occluded_of_two{};

  static constexpr int slot(int width) { return width == 2 ? 0 : (width == 4 ? 1 : 2); }
  bool walks(int width) const { return closest[static_cast<std::size_t>(slot(width))] != nullptr; }
  void closest_hits(const RaySoA& rays, const S& prims, const Bvh& bvh, HitSoA& hits,
                    BvhTraversal traversal = BvhTraversal::automatic) const {
    closest_hits(rays, BvhStores<S, 1>{&prims}, bvh, hits, traversal);
  }
  void any_hits(const RaySoA& rays, const S& prims, const Bvh& bvh, OcclusionSoA& result,
                BvhTraversal traversal = BvhTraversal::automatic) const {
    any_hits(rays, BvhStores<S, 1>{&prims}, bvh, result, traversal);
  }
  template <int K>
  void closest_hits(const RaySoA& rays, BvhStores<S, K> stores, const Bvh& bvh, HitSoA& hits,
                    BvhTraversal traversal = BvhTraversal::automatic) const {
    require_width(bvh.width);
    if constexpr (K == 1) {
      closest[slot(bvh.width)](rays, stores, bvh, hits, traversal);
    } else {
      closest_of_two[slot(bvh.width)](rays, stores, bvh, hits, traversal);
    }
  }
  template <int K>
  void any_hits(const RaySoA& rays, BvhStores<S, K> stores, const Bvh& bvh, OcclusionSoA& result,
                BvhTraversal traversal = BvhTraversal::automatic) const {
    require_width(bvh.width);
    if constexpr (K == 1) {
      occluded[slot(bvh.width)](rays, stores, bvh, result, traversal);
    } else {
      occluded_of_two[slot(bvh.width)](rays, stores, bvh, result, traversal);
    }
  }
  void require_width(int width) const {
    if (!walks(width)) throw_missing_node_width(width);
  }
};

inline namespace QUIVER_UNIT_NAMESPACE {

// Every active lane's direction in one octant.
template <class F>
inline bool same_octant(const Ray<F>& ray, const Mask<F>& active) {
  for (int a = 0; a < 3; ++a) {
    const Mask<F> negative = ray.direction[a] < F(0.f);
    if (any(negative && active) && any(and_not(active, negative))) return false;
  }
  return true;
}

// Stores whose incoherent packets walk ray by ray: triangles, whose leaves
// a lone ray scans several triangles at a time. Polygon packets stay
// together (a lone ray tests polygons one at a time); so do spheres and
// cones, whose reflection rays, what a Whitted renderer traces, stay
// coherent enough to share a walk.
template <class S>
concept IncoherentRaysTraverseAlone = S::kIncoherentRaysTraverseAlone;

// Whether the packet's active lanes walk the tree together: never when one
// reaches behind its origin (the packet walks' slab tests need tmin >= 0),
// else as the traversal says; automatic: triangles only within one octant.
// Any-hit packets follow the same rule as closest-hit ones.
template <class S, class F>
inline bool travels_together(BvhTraversal traversal, const Ray<F>& ray, const Mask<F>& active) {
  if (traversal == BvhTraversal::single || reaches_behind(ray, active)) return false;
  if (traversal == BvhTraversal::packets) return true;
  if (lane_count<F> == 1) return false;
  if constexpr (IncoherentRaysTraverseAlone<S>) {
    return same_octant(ray, active);
  } else {
    return true;
  }
}

// The active lanes that enter some child of the root within [tmin, tmax],
// in one packet test: a ray walked alone pays for its own setup (node
// terms, frame) before its first node test, and one leaving a surface into
// open space is done at the root. All active lanes when one reaches behind
// its origin (the packet slab test needs tmin >= 0), and for one-lane
// units (the test would be the walk's own first step). The lanes left out
// could not enter a child in their own walks either (the same slab test,
// lane by lane), so no hit changes.
template <int N, class F>
inline unsigned lanes_entering_root(const Bvh& bvh, const Ray<F>& ray, const F& tmax, const Mask<F>& active) {
  if (lane_count<F> == 1 || reaches_behind(ray, active)) return lane_bits(active);
  const PacketSlab<F, N> slab(ray, active);
  const float* root = BvhNodes<N>(bvh).block(0);
  Mask<F> entered(false);
  for (int c = 0; c < N; ++c) {
    F near;
    entered = entered || slab.enters(root, c, ray.tmin, tmax, near);
  }
  return lane_bits(entered && active);
}

template <KernelUnit U, class Method, class S, int N, int K>
[[gnu::flatten]] void closest_bvh(const RaySoA& rays, BvhStores<S, K> stores, const Bvh& bvh, HitSoA& hits,
                                  BvhTraversal traversal) {
  using F = UnitLanes<U>;
  constexpr std::size_t W = lane_count<F>;
  for (std::size_t first = 0; first < rays.count; first += W) {
    const Mask<F> active = first_lanes<F>(rays.count - first);
    const Ray<F> ray = rays.load<F>(first);
    if (travels_together<S>(traversal, ray, active)) {
      Hit<F> hit = hits.load<F>(first);
      const PacketSlab<F, N> slab(ray, active);
      const NodeFrustum<U, N> frustum(slab, ray.tmin, hit.t, active);
      if (frustum.usable) {
        closest_bvh_packet<true, U, Method>(stores, bvh, ray, slab, frustum, active, hit);
      } else {
        closest_bvh_packet<false, U, Method>(stores, bvh, ray, slab, frustum, active, hit);
      }
      hits.store(first, hit);
      continue;
    }
    const unsigned lanes = lanes_entering_root<N>(bvh, ray, load_lanes<F>(hits.t.data() + first), active);
    if constexpr (WalksLanesByFrame<Method, S, F>) {
      closest_bvh_lanes<U, Method, N>(stores, bvh, rays, first, lanes, hits);
      continue;
    }
    for (unsigned rest = lanes; rest != 0; rest &= rest - 1) {
      const std::size_t r = first + static_cast<std::size_t>(__builtin_ctz(rest));
      Hit<float> hit = hits.get(r);
      closest_bvh_single<U, Method, N>(stores, bvh, rays.get(r), hit);
      hits.set(r, hit);
    }
  }
}

template <KernelUnit U, class Method, class S, int N, int K>
[[gnu::flatten]] void occluded_bvh(const RaySoA& rays, BvhStores<S, K> stores, const Bvh& bvh,
                                   OcclusionSoA& result, BvhTraversal traversal) {
  using F = UnitLanes<U>;
  constexpr std::size_t W = lane_count<F>;
  for (std::size_t first = 0; first < rays.count; first += W) {
    const Mask<F> valid = first_lanes<F>(rays.count - first);
    const Ray<F> ray = rays.load<F>(first);
    const Mask<F> occluded = nonzero_lanes(load_int_lanes<F>(result.occluded.data() + first)) && valid;
    const Mask<F> open = and_not(valid, occluded);
    if (none(open)) continue;
    if (travels_together<S>(traversal, ray, open)) {
      // No frustum over two stores: the walk skips the untested store's
      // children without a box test, which leaves the frustum too little to
      // save for its setup per packet.
      const PacketSlab<F, N> slab(ray, open);
      const NodeFrustum<U, N> frustum =
          K == 1 ? NodeFrustum<U, N>(slab, ray.tmin, ray.tmax, open) : NodeFrustum<U, N>();
      const Mask<F> blocked =
          frustum.usable ? occluded_bvh_packet<true, U, Method>(stores, bvh, ray, slab, frustum, occluded, valid)
                         : occluded_bvh_packet<false, U, Method>(stores, bvh, ray, slab, frustum, occluded, valid);
      store_int_lanes<F>(select(blocked, IntLanes<F>(1), IntLanes<F>(0)), result.occluded.data() + first);
      continue;
    }
    const unsigned lanes = lanes_entering_root<N>(bvh, ray, ray.tmax, open);
    if constexpr (WalksLanesByFrame<Method, S, F>) {
      occluded_bvh_lanes<U, Method, N>(stores, bvh, rays, first, lanes, result);
      continue;
    }
    for (unsigned rest = lanes; rest != 0; rest &= rest - 1) {
      const std::size_t r = first + static_cast<std::size_t>(__builtin_ctz(rest));
      if (occluded_bvh_single<U, Method, N>(stores, bvh, rays.get(r))) {
        result.occluded[r] = 1;
      }
    }
  }
}

// Fills node width N's walks: over one store and over two.
template <KernelUnit U, class Method, class S, int N>
void add_bvh_width(BvhStreams<S>& s) {
  constexpr std::size_t k = static_cast<std::size_t>(BvhStreams<S>::slot(N));
  s.closest[k] = &closest_bvh<U, Method, S, N, 1>;
  s.occluded[k] = &occluded_bvh<U, Method, S, N, 1>;
  s.closest_of_two[k] = &closest_bvh<U, Method, S, N, 2>;
  s.occluded_of_two[k] = &occluded_bvh<U, Method, S, N, 2>;
}

// The product's walks: node width kProductNodeWidth.
template <KernelUnit U, class Method, class S>
BvhStreams<S> make_bvh_streams() {
  BvhStreams<S> s;
  add_bvh_width<U, Method, S, kProductNodeWidth>(s);
  return s;
}

}  // namespace QUIVER_UNIT_NAMESPACE
}  // namespace quiver
