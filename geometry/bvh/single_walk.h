// The single-ray walks: one ray tests all children of a wide node at once
// (a node's boxes are SoA), nearest child first; leaves test the ray
// against W primitives at a time (the scan kernels), or one at a time for
// kinds without a scan orientation. Methods with a per-ray frame (the
// watertight triangle test) get one walk per frame, chosen once per ray.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "geometry/bvh/node_ray.h"
#include "geometry/bvh/stack.h"
#include "geometry/bvh/stores.h"
#include "geometry/leaf_loops.h"

namespace quiver {
inline namespace QUIVER_UNIT_NAMESPACE {

// One ray prepared once for its leaf tests: broadcast to the unit's lanes
// for stores with a scan orientation, as it is otherwise.
template <KernelUnit U, class Method, class S>
auto prepare_for_leaves(const Ray<float>& ray) {
  if constexpr (ScanStore<S>) {
    return Method::prepare(broadcast_ray<LeafScanLanes<U>>(ray));
  } else {
    return Method::prepare(ray);
  }
}

// Method::intersect, flattened on its own. GCC leaves the one-ray (float)
// test of a kind without a scan orientation out of line in the single-ray
// walks, which keeps the walk's own loop small.
template <KernelUnit U, class Method, class Prepared, class L, class F>
[[gnu::flatten]] inline Mask<F> intersect_in_unit(const Prepared& prepared, const L& prims, const F& tmax,
                                                  const Mask<F>& active, Candidate<F>& out) {
  return Method::intersect(prepared, prims, tmax, active, out);
}

// One ray's leaf tests in the single-ray walks of unit U: the method's
// prepared ray and, for a method with a per-ray frame (the watertight
// triangle test), that frame fixed at compile time (Axes; void: the method's
// own intersect).
template <KernelUnit U, class Method, class Prepared, class Axes>
struct LeafRay {
  Prepared prepared;

  template <class L, class F>
  Mask<F> intersect(const L& prims, const F& tmax, const Mask<F>& active, Candidate<F>& out) const {
    if constexpr (std::is_void_v<Axes>) {
      return intersect_in_unit<U, Method>(prepared, prims, tmax, active, out);
    } else {
      return Method::template intersect_in<Axes>(prepared, prims, tmax, active, out);
    }
  }
};

template <class Method, class F>
concept FixesAxesPerRay = requires(const Ray<float>& ray) {
  Method::template with_fixed_axes<F>(ray, [](const auto&, auto) {});
};

// Hands a prepared ray and its compile-time frame to walk as a LeafRay.
// (Named functors, not lambdas: GCC's flatten left lambdas out of line.)
template <KernelUnit U, class Method, class Walk>
struct WalkInFrame {
  const Walk& walk;

  template <class Prepared, class Axes>
  [[gnu::always_inline]] void operator()(const Prepared& prepared, Axes) const {
    walk(LeafRay<U, Method, Prepared, Axes>{prepared});
  }
};

// Calls walk(leaf_ray) with the method's own leaf test.
template <KernelUnit U, class Method, class S, class Walk>
[[gnu::always_inline]] inline void with_plain_leaf_ray(const Ray<float>& ray, const Walk& walk) {
  using Prepared = decltype(prepare_for_leaves<U, Method, S>(ray));
  walk(LeafRay<U, Method, Prepared, void>{prepare_for_leaves<U, Method, S>(ray)});
}

// Calls walk(leaf_ray). A scan with a per-ray frame gets one walk per frame
// (six), chosen once per ray, so no leaf block pays for choosing it.
template <KernelUnit U, class Method, class S, class Walk>
[[gnu::always_inline]] inline void with_leaf_ray(const Ray<float>& ray, const Walk& walk) {
  using F = LeafScanLanes<U>;
  if constexpr (ScanStore<S> && FixesAxesPerRay<Method, F>) {
    Method::template with_fixed_axes<F>(ray, WalkInFrame<U, Method, Walk>{walk});
  } else {
    with_plain_leaf_ray<U, Method, S>(ray, walk);
  }
}

// A single-ray walk run with its node tests on the distances' bits (kBits)
// or on the floats.
template <bool kBits, class Walk>
struct WithNodeTests {
  const Walk& walk;

  template <class Leaf>
  [[gnu::always_inline]] void operator()(const Leaf& leaf_ray) const {
    walk.template run<kBits>(leaf_ray);
  }
};

// Runs a single-ray walk. Scan stores: a ray whose node tests may compare
// distances by their bits (NodeRay::bits_ordered) through with_leaf_ray,
// any other (a negative or NaN tmin, a non-finite direction or an origin so
// far off that o/d overflows: rays no renderer makes) through one plain
// copy with float node tests (which enter every child of a ray reaching
// behind its origin, NodeRay::tmin). Other kinds keep one copy, on the
// floats: their per-ray setup outweighs the node tests, so the bits would
// save little and a second copy would cost code.
template <KernelUnit U, class Method, class S, class Walk>
[[gnu::always_inline]] inline void run_single_walk(const Ray<float>& ray, const Walk& walk) {
  if constexpr (!ScanStore<S>) {
    with_plain_leaf_ray<U, Method, S>(ray, WithNodeTests<false, Walk>{walk});
  } else if (walk.node_ray.bits_ordered) [[likely]] {
    with_leaf_ray<U, Method, S>(ray, WithNodeTests<true, Walk>{walk});
  } else {
    with_plain_leaf_ray<U, Method, S>(ray, WithNodeTests<false, Walk>{walk});
  }
}

// A single-ray walk's stack entry: a node and its entry distance (the sort key).
struct SingleStackEntry {
  std::int32_t node;
  float near;
};

// The closest-hit walk of one ray: descends into the nearest entered child
// directly and pushes the others, farthest first; a popped entry is culled
// against the current hit. The hit is a local copy (stores through a
// reference kept the tree's fields from staying in registers).
template <KernelUnit U, int N, bool kBits, class S, int K, class Leaf>
[[gnu::always_inline]] inline Hit<float> closest_single_walk(BvhStores<S, K> stores, BvhNodes<N> nodes,
                                                             const NodeRay<U, N>& node_ray, const Leaf& leaf_ray,
                                                             Hit<float> hit) {
  using F = LeafScanLanes<U>;
  std::array<SingleStackEntry, bvh_stack_size(N)> stack;
  const auto key_at = [&](std::size_t i) __attribute__((always_inline)) { return stack[i].near; };
  const auto move_up = [&](std::size_t i) __attribute__((always_inline)) { stack[i] = stack[i - 1]; };
  std::size_t top = 0;
  std::int32_t current = 0;
  for (;;) {
    if (is_leaf(current)) {
      const S& prims = stores.of(current);
      const std::size_t first = static_cast<std::size_t>(leaf_first(current));
      // A leaf of an untested store: an empty range.
      const std::size_t end = stores.tests(current) ? first + static_cast<std::size_t>(leaf_count(current)) : first;
      if constexpr (ScanStore<S>) {
        closest_by_blocks<F>(leaf_ray, prims, first, end, hit);
      } else {
        closest_one_by_one<float>(leaf_ray, prims, first, end, true, hit);
      }
    } else {
      ChildKeys<N> near;
      const float* block = nodes.block(current);
      unsigned bits = enter_children<N, kBits>(block, node_ray, hit.t, near);
      // Empty slots have empty boxes, which no ray enters (and hold no primitive).
      if (bits != 0) {
        int c = __builtin_ctz(bits);
        bits &= bits - 1;
        if (bits == 0) {  // one child: no stack traffic
          current = BvhNodes<N>::child(block, c);
          continue;
        }
        // Several: push all, farthest first, then take the nearest.
        const std::size_t base = top;
        for (;;) {
          stack[sorted_slot(base, top++, near[c], key_at, move_up)] = {BvhNodes<N>::child(block, c), near[c]};
          if (bits == 0) break;
          c = __builtin_ctz(bits);
          bits &= bits - 1;
        }
        current = stack[--top].node;
        continue;
      }
    }
    // Next: the nearest pending entry the current hit does not cull.
    for (;;) {
      if (top == 0) return hit;
      const SingleStackEntry entry = stack[--top];
      if (entry.near <= hit.t * (1.f + kSlabSlack)) {
        current = entry.node;
        break;
      }
    }
  }
}

// The closest-hit walk as a functor of its leaf tests (see with_leaf_ray).
template <KernelUnit U, int N, class S, int K>
struct ClosestSingleWalk {
  BvhStores<S, K> stores;
  BvhNodes<N> nodes;
  const NodeRay<U, N>& node_ray;
  Hit<float>& hit;

  template <bool kBits, class Leaf>
  [[gnu::always_inline]] void run(const Leaf& leaf_ray) const {
    hit = closest_single_walk<U, N, kBits>(stores, nodes, node_ray, leaf_ray, hit);
  }
};

// Out of line and flattened on its own: inlined into the packet stream it
// shared that function's registers and spilled its loop state.
template <KernelUnit U, class Method, int N, class S, int K>
[[gnu::noinline, gnu::flatten]] void closest_bvh_single(BvhStores<S, K> stores, const Bvh& bvh,
                                                        const Ray<float>& ray, Hit<float>& hit) {
  const NodeRay<U, N> node_ray(ray);
  run_single_walk<U, Method, S>(ray, ClosestSingleWalk<U, N, S, K>{stores, BvhNodes<N>(bvh), node_ray, hit});
}

// The any-hit walk of one ray: stops at its first hit.
template <KernelUnit U, int N, bool kBits, class S, int K, class Leaf>
[[gnu::always_inline]] inline bool occluded_single_walk(BvhStores<S, K> stores, BvhNodes<N> nodes,
                                                        const NodeRay<U, N>& node_ray, const Leaf& leaf_ray,
                                                        float tmax) {
  using F = LeafScanLanes<U>;
  std::array<std::int32_t, bvh_stack_size(N)> stack;
  std::size_t top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const std::int32_t entry = stack[--top];
    if (is_leaf(entry)) {
      const S& prims = stores.of(entry);
      const std::size_t first = static_cast<std::size_t>(leaf_first(entry));
      const std::size_t end = first + static_cast<std::size_t>(leaf_count(entry));
      if constexpr (ScanStore<S>) {
        if (occluded_by_blocks<F>(leaf_ray, prims, first, end, tmax)) return true;
      } else {
        if (occluded_one_by_one<float>(leaf_ray, prims, first, end, true, tmax, false)) return true;
      }
      continue;
    }
    ChildKeys<N> near;
    const float* block = nodes.block(entry);
    for (unsigned bits = enter_children<N, kBits>(block, node_ray, tmax, near); bits != 0;
         bits &= bits - 1) {
      // Never an empty slot (empty boxes are never entered); the test is
      // kept on purpose: this loop runs slower without it.
      const std::int32_t child = BvhNodes<N>::child(block, __builtin_ctz(bits));
      if (worth_entering(stores, child)) stack[top++] = child;
    }
  }
  return false;
}

// The any-hit walk as a functor of its leaf tests.
template <KernelUnit U, int N, class S, int K>
struct OccludedSingleWalk {
  BvhStores<S, K> stores;
  BvhNodes<N> nodes;
  const NodeRay<U, N>& node_ray;
  float tmax;
  bool& blocked;

  template <bool kBits, class Leaf>
  [[gnu::always_inline]] void run(const Leaf& leaf_ray) const {
    blocked = occluded_single_walk<U, N, kBits>(stores, nodes, node_ray, leaf_ray, tmax);
  }
};

// Out of line and flattened on its own, as closest_bvh_single.
template <KernelUnit U, class Method, int N, class S, int K>
[[gnu::noinline, gnu::flatten]] bool occluded_bvh_single(BvhStores<S, K> stores, const Bvh& bvh,
                                                        const Ray<float>& ray) {
  const NodeRay<U, N> node_ray(ray);
  bool blocked = false;
  run_single_walk<U, Method, S>(ray, OccludedSingleWalk<U, N, S, K>{stores, BvhNodes<N>(bvh), node_ray, ray.tmax,
                                                                    blocked});
  return blocked;
}

}  // namespace QUIVER_UNIT_NAMESPACE
}  // namespace quiver
