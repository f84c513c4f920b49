// The packet walks: W rays walk the tree together (Wald, Slusallek,
// Benthin, Wagner, "Interactive rendering with coherent ray tracing",
// 2001); a child is entered when any active lane's slab interval meets it;
// a popped entry keeps only the lanes whose entry distance is still within
// their closest hit; leaves test W rays against one primitive at a time
// (the packet kernels). When the active lanes share an octant, an interval
// frustum around them first tests all of a node's children at once, and
// only the children it enters are tested lane by lane (NodeFrustum; any-hit
// packets: through a tree over one store). Closest and any hit as in
// geometry/leaf_loops.h.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "geometry/bvh/node_ray.h"
#include "geometry/bvh/stack.h"
#include "geometry/bvh/stores.h"
#include "geometry/leaf_loops.h"

namespace quiver {
inline namespace QUIVER_UNIT_NAMESPACE {

// Calls visit(c) for the children c of an N-wide node a packet tests, in
// order (kLastFirst: N-1 down to 0): without a frustum every child, in a
// counted loop; after one (kSome) the children in `candidates`, bit by bit.
// Two forms chosen at compile time: the counted loop unrolls, the bit loop
// skips the children the frustum ruled out.
template <int N, bool kSome, bool kLastFirst, class Visit>
[[gnu::always_inline]] inline void for_each_child(unsigned candidates, const Visit& visit) {
  if constexpr (!kSome) {
    for (int i = 0; i < N; ++i) visit(kLastFirst ? N - 1 - i : i);
  } else {
    while (candidates != 0) {
      const int c = kLastFirst ? 31 - __builtin_clz(candidates) : __builtin_ctz(candidates);
      candidates &= ~(1u << c);
      visit(c);
    }
  }
}

// kCulls: the frustum is usable and tests each node's children first.
template <bool kCulls, KernelUnit U, class Method, int N, class S, int K, class F = UnitLanes<U>>
[[gnu::always_inline]] inline void closest_bvh_packet(BvhStores<S, K> stores, const Bvh& bvh, const Ray<F>& ray,
                                                      const PacketSlab<F, N>& slab,
                                                      const NodeFrustum<U, N>& frustum, const Mask<F>& active,
                                                      Hit<F>& hit) {
  // Nodes and their lanes' entry distances (+inf in lanes that do not
  // enter), in two arrays: an entry copied as one struct is stored in 16-byte
  // halves and reloaded whole, which defeats store forwarding.
  std::array<std::int32_t, bvh_stack_size(N)> stack_node;
  std::array<F, bvh_stack_size(N)> stack_near;
  const BvhNodes<N> nodes(bvh);
  const auto prepared = Method::prepare(ray);
  const MethodTest<Method, decltype(prepared)> test{prepared};
  const F inf(std::numeric_limits<float>::infinity());
  // The frustum's tmax: the largest active lane's closest hit so far.
  float frustum_tmax = frustum.tmax;
  std::size_t top = 0;
  stack_node[top] = 0;
  stack_near[top++] = select(active, ray.tmin, inf);
  while (top > 0) {
    --top;
    const std::int32_t entry_node = stack_node[top];
    const Mask<F> lanes = stack_near[top] <= hit.t * F(1.f + kSlabSlack);
    if (none(lanes)) continue;
    if (is_leaf(entry_node)) {
      const std::size_t first = static_cast<std::size_t>(leaf_first(entry_node));
      const bool changed = closest_one_by_one<F>(test, stores.of(entry_node), first,
                                                 first + static_cast<std::size_t>(leaf_count(entry_node)), lanes, hit);
      if constexpr (kCulls) {
        if (changed) frustum_tmax = horizontal_max(select(active, hit.t, -inf));
      }
      continue;
    }
    // Children that some lane enters, pushed farthest first, sorted by their smallest lane's entry distance.
    std::array<float, bvh_stack_size(N)> key;
    const std::size_t base = top;
    const float* block = nodes.block(entry_node);
    const auto key_at = [&](std::size_t i) __attribute__((always_inline)) { return key[i]; };
    const auto move_up = [&](std::size_t i) __attribute__((always_inline)) {
      key[i] = key[i - 1];
      stack_node[i] = stack_node[i - 1];
      stack_near[i] = stack_near[i - 1];
    };
    const auto push = [&](std::int32_t child, const F& lane_near) __attribute__((always_inline)) {
      const float k = horizontal_min(lane_near);
      const std::size_t at = sorted_slot(base, top++, k, key_at, move_up);
      key[at] = k;
      stack_node[at] = child;
      stack_near[at] = lane_near;
    };
    if constexpr (kCulls) {
      ChildKeys<N> unused;
      const unsigned candidates = enter_children<N>(block, frustum, frustum_tmax, unused);
      for_each_child<N, true, false>(candidates, [&](int c) __attribute__((always_inline)) {
        const std::int32_t child = BvhNodes<N>::child(block, c);
        if constexpr (K == 2) {
          if (!worth_entering(stores, child)) return;
        }
        F near;
        const Mask<F> enters = slab.enters(block, c, ray.tmin, hit.t, near) && lanes;
        if (any(enters)) push(child, select(enters, near, inf));
      });
    } else {
      // Every child tested first, then the entered ones pushed: no branch on entered lanes between the tests.
      std::array<F, N> child_near;
      unsigned entered = 0;
      for (int c = 0; c < N; ++c) {
        // One store: no check, an empty slot's empty box lets no lane in, so a check would only add work.
        if constexpr (K == 2) {
          if (!worth_entering(stores, BvhNodes<N>::child(block, c))) continue;
        }
        F near;
        const Mask<F> enters = slab.enters(block, c, ray.tmin, hit.t, near) && lanes;
        child_near[c] = select(enters, near, inf);
        entered |= static_cast<unsigned>(any(enters)) << c;
      }
      for (; entered != 0; entered &= entered - 1) {
        const int c = __builtin_ctz(entered);
        push(BvhNodes<N>::child(block, c), child_near[c]);
      }
    }
  }
}

// kCulls as in closest_bvh_packet; the slab and the frustum are set up for the lanes open at the start.
template <bool kCulls, KernelUnit U, class Method, int N, class S, int K, class F = UnitLanes<U>>
[[gnu::always_inline]] inline Mask<F> occluded_bvh_packet(BvhStores<S, K> stores, const Bvh& bvh,
                                                          const Ray<F>& ray, const PacketSlab<F, N>& slab,
                                                          const NodeFrustum<U, N>& frustum, Mask<F> occluded,
                                                          const Mask<F>& valid) {
  // Nodes and the lanes that entered them, in two arrays (see closest_bvh_packet).
  std::array<std::int32_t, bvh_stack_size(N)> stack_node;
  std::array<Mask<F>, bvh_stack_size(N)> stack_lanes;
  const BvhNodes<N> nodes(bvh);
  const auto prepared = Method::prepare(ray);
  const MethodTest<Method, decltype(prepared)> test{prepared};
  std::size_t top = 0;
  stack_node[top] = 0;
  stack_lanes[top++] = valid;
  while (top > 0) {
    if (none(and_not(valid, occluded))) break;
    --top;
    const std::int32_t entry_node = stack_node[top];
    const Mask<F> entry_lanes = stack_lanes[top];
    const Mask<F> active = and_not(entry_lanes, occluded);
    if (none(active)) continue;
    if (is_leaf(entry_node)) {
      const std::size_t first = static_cast<std::size_t>(leaf_first(entry_node));
      occluded = occluded_one_by_one<F>(test, stores.of(entry_node), first,
                                        first + static_cast<std::size_t>(leaf_count(entry_node)), entry_lanes,
                                        ray.tmax, occluded);
      continue;
    }
    const float* block = nodes.block(entry_node);
    unsigned candidates = 0;
    if constexpr (kCulls) {
      ChildKeys<N> unused;
      candidates = enter_children<N>(block, frustum, frustum.tmax, unused);
    }
    for_each_child<N, kCulls, true>(candidates, [&](int c) __attribute__((always_inline)) {
      const std::int32_t child = BvhNodes<N>::child(block, c);
      if constexpr (K == 2) {  // as in closest_bvh_packet
        if (!worth_entering(stores, child)) return;
      }
      F near;
      const Mask<F> enters = slab.enters(block, c, ray.tmin, ray.tmax, near) && active;
      if (any(enters)) {
        stack_node[top] = child;
        stack_lanes[top++] = enters;
      }
    });
  }
  return occluded;
}

}  // namespace QUIVER_UNIT_NAMESPACE
}  // namespace quiver
