// A primitive store in BVH leaf order, with its BVH: the store is built, its
// BVH built over the primitive boxes, and the store built a second time from
// the input in leaf order (builders are deterministic, so they keep the same
// primitives). source[k] names the input index of stored primitive k.
#pragma once

#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

#include "geometry/build_report.h"
#include "geometry/bvh.h"
#include "geometry/primitive_bounds.h"

namespace quiver {

// Rebuilds `store` (built by builder from descs) in the leaf order of a new
// BVH, which it returns.
template <class Store, class Desc, class Builder>
Bvh reorder_for_bvh(std::span<const Desc> descs, Builder builder, const BvhBuildOptions& options, Store& store) {
  std::vector<std::uint32_t> order;
  Bvh bvh = build_bvh(primitive_boxes(store), options, order);
  std::vector<Desc> in_leaf_order;
  in_leaf_order.reserve(order.size());
  for (std::uint32_t k : order) in_leaf_order.push_back(descs[store.source[k]]);
  BuildReport again;
  Store reordered = builder(std::span<const Desc>(in_leaf_order), again);
  if (reordered.count != store.count) throw std::logic_error("a store kept different primitives when reordered");
  for (std::size_t k = 0; k < order.size(); ++k) reordered.source[k] = store.source[order[k]];
  store = std::move(reordered);
  return bvh;
}

}  // namespace quiver
