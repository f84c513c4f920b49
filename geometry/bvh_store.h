// A primitive store in BVH leaf order, with its BVH: the store is built, its
// BVH built over the primitive boxes, and the store put in leaf order: its
// columns gathered when they hold every per-primitive field, else built a
// second time from the input in leaf order (builders are deterministic and
// treat each primitive alike whatever the order, so either way the values
// are those a build in leaf order gives). source[k] names the input index of
// stored primitive k. Two stores of one kind can share one BVH, each in the
// order of its own leaves.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

#include "geometry/build_report.h"
#include "geometry/bvh.h"
#include "geometry/desc_refs.h"
#include "geometry/parallel_indices.h"
#include "geometry/primitive_bounds.h"
#include "geometry/soa.h"

namespace quiver {

// Stores reordered by gathering their columns.
template <class Store>
concept ColumnsHoldEveryField = Store::kColumnsHoldEveryField;

// Puts the store's primitives at `positions` (indices into it) in that
// order, columns padded as a builder pads them; source gathered alike. One
// column at a time, so the store is not held twice, each gathered into the
// memory of the column before it (fresh pages cost more than the copy).
template <ColumnsHoldEveryField Store>
void gather(Store& store, std::span<const std::uint32_t> positions) {
  const std::size_t padded = padded_size(positions.size());
  AlignedFloats spare;
  for (AlignedFloats* column : store.columns()) {
    if (column->empty()) continue;  // an optional column left out
    spare.clear();
    if (spare.capacity() != padded) {
      AlignedFloats().swap(spare);
      spare.reserve(padded);  // exactly: padding grows no further
    }
    spare.resize(positions.size());
    for_each_index(positions.size(), [&](std::size_t k) { spare[k] = (*column)[positions[k]]; });
    pad_column(spare, positions.size());
    column->swap(spare);
  }
  std::vector<std::uint32_t> source(positions.size());
  for_each_index(positions.size(), [&](std::size_t k) { source[k] = store.source[positions[k]]; });
  store.source = std::move(source);
  store.count = positions.size();
}

// The store's primitives at `positions`, in that order, built again by
// builder from their descriptions (for stores whose columns are not all
// per primitive, as polygons' vertex lists).
template <class Store, class Desc, class Builder>
Store rebuilt(const Store& store, const DescRefs<Desc>& descs, std::span<const std::uint32_t> positions,
              Builder builder) {
  std::vector<std::uint32_t> source;  // input indices in leaf order
  source.reserve(positions.size());
  for (std::uint32_t p : positions) source.push_back(store.source[p]);
  DescRefs<Desc> in_leaf_order;
  in_leaf_order.reserve(source.size());
  for (std::uint32_t i : source) in_leaf_order.push_back(descs[i]);
  BuildReport again;
  Store reordered = builder(in_leaf_order, again);
  if (reordered.count != store.count) throw std::logic_error("a store kept different primitives when reordered");
  reordered.source = std::move(source);
  reordered.id_base = store.id_base;
  return reordered;
}

// Rebuilds `store` (built by builder from descs) in the leaf order of a new
// BVH, which it returns.
template <class Store, class Desc, class Builder>
Bvh reorder_for_bvh(const DescRefs<Desc>& descs, Builder builder, const BvhBuildOptions& options, Store& store) {
  Store none;
  return reorder_for_bvh(descs, store, DescRefs<Desc>(), none, builder, options);
}

// Rebuilds two stores of one kind (each built by builder from its descs) in
// the leaf order of one new BVH over both, which it returns: its leaves
// index store `first` as store 0 and `second` as store 1. With
// leaf_positions, (*leaf_positions)[s][k] is the position in store s before
// the reorder of its primitive k after.
template <class Store, class Desc, class Builder>
Bvh reorder_for_bvh(const DescRefs<Desc>& first_descs, Store& first, const DescRefs<Desc>& second_descs,
                    Store& second, Builder builder, const BvhBuildOptions& options,
                    std::array<std::vector<std::uint32_t>, 2>* leaf_positions = nullptr) {
  const std::size_t count = first.count + second.count;
  const auto box_of = [&](std::size_t i) {
    return i < first.count ? primitive_box(first, i) : primitive_box(second, i - first.count);
  };
  std::vector<std::uint8_t> store_of;
  if (second.count > 0) {
    store_of.assign(first.count, 0);
    store_of.resize(count, 1);
  }
  std::vector<std::uint32_t> order;
  Bvh bvh = build_bvh(count, box_of, options, order, store_of);
  const std::array<Store*, 2> stores{&first, &second};
  const std::array<const DescRefs<Desc>*, 2> descs{&first_descs, &second_descs};
  for (std::size_t s = 0; s < 2; ++s) {
    Store& store = *stores[s];
    if (store.count == 0) continue;
    const std::uint32_t base = s == 0 ? 0 : static_cast<std::uint32_t>(first.count);
    std::vector<std::uint32_t> positions;  // the store's primitives in leaf order
    positions.reserve(store.count);
    for (std::uint32_t k : order) {
      if (k >= base && k - base < store.count) positions.push_back(k - base);
    }
    if constexpr (ColumnsHoldEveryField<Store>) {
      gather(store, positions);
    } else {
      store = rebuilt(store, *descs[s], positions, builder);
    }
    if (leaf_positions != nullptr) (*leaf_positions)[s] = std::move(positions);
  }
  return bvh;
}

}  // namespace quiver
