// The stores a BVH query walks through and tests, and how its walks test
// a leaf's primitives: the scan orientation (one ray, W primitives) where the
// store has one, in LeafScanLanes.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "geometry/bvh.h"

namespace quiver {

enum class BvhTraversal { automatic, packets, single };

// Lanes for one ray against a leaf's primitives (the scan kernels): the
// unit's own, but 8 in the 16-wide unit, whose leaves (at most 8
// primitives by default) would leave half of 16 lanes empty.
template <KernelUnit U>
struct LeafScanLanesOf {
  using type = UnitLanes<U>;
};
#if XSIMD_WITH_AVX512BW
template <>
struct LeafScanLanesOf<KernelUnit::avx512> {
  using type = UnitLanes<KernelUnit::avx2>;
};
#endif
template <KernelUnit U>
using LeafScanLanes = typename LeafScanLanesOf<U>::type;

// Primitive stores with a scan orientation (one ray, W primitives).
template <class S>
concept ScanStore = requires(const S& s) { s.template load<float>(0); };

// The stores a query walks through a BVH and tests. K = 1: the tree's one
// store, every leaf tested (its store bit is not read). K = 2: the tree
// indexes two stores (leaf_store picks one, both non-null) and the query
// tests those in `tested` (bit s for store s): the packet walks and the
// any-hit walk never push a leaf of the others, the closest-hit single-ray
// walk may reach one and tests nothing in it. One store is a compile-time
// case, so its walks choose no store per leaf.
template <class S, int K>
struct BvhStores;

template <class S>
struct BvhStores<S, 1> {
  const S* store;

  [[gnu::always_inline]] static constexpr bool tests(std::int32_t) { return true; }
  [[gnu::always_inline]] const S& of(std::int32_t) const { return *store; }
};

template <class S>
struct BvhStores<S, 2> {
  std::array<const S*, 2> store;
  unsigned tested;

  [[gnu::always_inline]] bool tests(std::int32_t leaf) const { return ((tested >> leaf_store(leaf)) & 1u) != 0; }
  [[gnu::always_inline]] const S& of(std::int32_t leaf) const {
    return *store[static_cast<std::size_t>(leaf_store(leaf))];
  }
};

// Calls through_tree(stores) with the stores a query of `tested` (bit s for
// store s) walks in a tree over `first` (store 0) and `second` (store 1):
// both (BvhStores<S, 2>) when both have primitives, else the one that has,
// when tested; not at all when nothing tested has primitives.
template <class S, class Fn>
inline void with_tested_stores(const S& first, const S& second, unsigned tested, Fn through_tree) {
  if (first.count > 0 && second.count > 0) {
    through_tree(BvhStores<S, 2>{{&first, &second}, tested});
  } else if (first.count > 0 && (tested & 1u) != 0) {
    through_tree(BvhStores<S, 1>{&first});
  } else if (second.count > 0 && (tested & 2u) != 0) {
    through_tree(BvhStores<S, 1>{&second});
  }
}

inline namespace QUIVER_UNIT_NAMESPACE {

// A child slot a walk enters: an inner node, or a non-empty leaf of a tested store.
template <class S, int K>
inline bool worth_entering(const BvhStores<S, K>& stores, std::int32_t child) {
  return !is_leaf(child) || (leaf_count(child) != 0 && stores.tests(child));
}

}  // namespace QUIVER_UNIT_NAMESPACE
}  // namespace quiver
