// A bounding volume hierarchy over one primitive store: binned SAH (Wald,
// "On fast construction of SAH-based bounding volume hierarchies", 2007) on
// a binary tree, collapsed into nodes of 2, 4 or 8 children whose boxes are
// stored SoA (lo x, y, z then hi x, y, z, `width` floats each), so one ray
// tests every child box of a node in one SIMD operation. A node's child
// slots follow its boxes in the same block (one run of cache lines).
//
// The build reorders the store: a leaf is a contiguous range of at most
// max_leaf_size primitives, so the leaf is an SoA block the scan kernels load
// directly. build_bvh returns that order (order[k] = input index of the
// primitive that goes to position k). One tree can index two stores of a
// kind: each leaf then holds one store's primitives and says which.
//
// Boxes are conservative: each primitive's box contains every point the
// kernel can report on it (see geometry/primitive_bounds.h), and the
// traversal widens the slab interval (geometry/bvh/slab.h), so culling
// never removes a primitive a brute-force scan would report.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "geometry/box.h"
#include "geometry/soa.h"

namespace quiver {

// Child slot of a wide node: >= 0 is an inner node, named by the float
// offset of its block (node index * node_floats), so that a walk reaches
// it with one add; < 0 a leaf holding
// primitives [first, first + count) of store 0 or 1 (a tree can index two
// stores of one kind, such as a scene's opaque and transmissive layers;
// count 0 is an empty slot).
inline constexpr std::int32_t kMaxLeafSize = 15;
constexpr std::int32_t encode_leaf(std::int32_t first, std::int32_t count, std::int32_t store = 0) {
  return -1 - ((first * 2 + store) * 16 + count);
}
constexpr bool is_leaf(std::int32_t child) { return child < 0; }
constexpr std::int32_t leaf_first(std::int32_t child) { return (-1 - child) / 32; }
constexpr std::int32_t leaf_count(std::int32_t child) { return (-1 - child) % 16; }
constexpr std::int32_t leaf_store(std::int32_t child) { return (-1 - child) / 16 % 2; }
// Largest primitive count a BVH can index, all stores together ((first * 2 +
// 1) * 16 + 15 must fit an int32).
inline constexpr std::size_t kMaxBvhPrimitives = std::size_t(1) << 26;

// The node width the product walks (geometry/bvh/bvh_streams.h): a shallower
// tree, a node's children tested together. The builder also makes 2 and 4,
// which the study streams walk (tests/support/study_streams.h).
inline constexpr int kProductNodeWidth = 8;

struct BvhBuildOptions {
  int width = kProductNodeWidth;  // children per node: 2, 4 or 8
  int max_leaf_size = 8;       // at most kMaxLeafSize
  int bins = 16;               // SAH bins per axis
  float traversal_cost = 4.f;  // relative to one primitive test
  std::size_t parallel_threshold = 4096;  // subtrees at least this big build in parallel (oneTBB)
};

// The node layout, for nodes of `width` children: node n's block starts at
// float n * node_floats(width); child slot c follows the boxes at
// child_slot(width, c) within it. Written once here for the builder, the
// walks (compile-time width) and code that reads any width.
constexpr std::size_t node_floats(std::size_t width) { return 7 * width; }
constexpr std::size_t child_slot(std::size_t width, int slot) { return 6 * width + static_cast<std::size_t>(slot); }

struct Bvh {
  int width = 0;  // 0: no BVH
  // Per node, 7 * width floats: the boxes (lo x, lo y, lo z, hi x, hi y,
  // hi z, width each), then the width child slots (int32 bits).
  AlignedFloats nodes;
  std::size_t node_count = 0;
  int depth = 0;  // deepest node, root = 1
  Box bounds{};   // of the whole store

  bool empty() const { return width == 0; }
  std::size_t node_floats() const { return quiver::node_floats(static_cast<std::size_t>(width)); }
  const float* boxes(std::size_t node) const { return nodes.data() + node * node_floats(); }
  std::int32_t child(std::size_t node, int slot) const {
    return std::bit_cast<std::int32_t>(boxes(node)[child_slot(static_cast<std::size_t>(width), slot)]);
  }
  // The index of an inner child (!is_leaf(child)).
  std::size_t node_of(std::int32_t child) const { return static_cast<std::size_t>(child) / node_floats(); }
  std::size_t memory_bytes() const { return nodes.capacity() * sizeof(float); }
};

inline namespace QUIVER_UNIT_NAMESPACE {

// The nodes of a tree of width N known at compile time (the traversal
// walks): the same layout at a constant stride.
template <int N>
struct BvhNodes {
  const float* data;

  explicit BvhNodes(const Bvh& bvh) : data(bvh.nodes.data()) {}
  // The block of an inner child slot's node; the root's is block(0).
  const float* block(std::int32_t node) const { return data + node; }
  static std::int32_t child(const float* block, unsigned slot) {
    return std::bit_cast<std::int32_t>(block[child_slot(N, 0) + slot]);
  }
};

}  // namespace QUIVER_UNIT_NAMESPACE

// Builds the BVH of `boxes` and the primitive order its leaves use. An empty
// input gives an empty Bvh. Throws std::length_error past kMaxBvhPrimitives
// (or if the node offsets would pass 2^31 floats, far beyond any tree of
// that many primitives seen) and std::invalid_argument for a bad width or
// leaf size.
// `store_of` (empty: every primitive in store 0) puts primitive i in store
// store_of[i] (0 or 1): each leaf then holds one store's primitives, and its
// range counts positions in that store's part of `order` (order filtered to
// the primitives of that store, in order).
Bvh build_bvh(std::span<const Box> boxes, const BvhBuildOptions& options, std::vector<std::uint32_t>& order,
              std::span<const std::uint8_t> store_of = {});
// The same over `count` primitives whose boxes box_of(i) gives, each asked
// for once, from any thread.
Bvh build_bvh(std::size_t count, const std::function<Box(std::size_t)>& box_of, const BvhBuildOptions& options,
              std::vector<std::uint32_t>& order, std::span<const std::uint8_t> store_of = {});

// Deepest tree the build makes: past kSahDepthLimit it splits at the object
// median, which halves the count per level (kMaxBvhPrimitives = 2^26: 26
// levels), then once by store.
inline constexpr int kSahDepthLimit = 32;
inline constexpr int kMaxBvhDepth = kSahDepthLimit + 27;
// A traversal stack never holds more entries than this: each level leaves at
// most width - 1 siblings behind.
constexpr std::size_t bvh_stack_size(int width) {
  return static_cast<std::size_t>(kMaxBvhDepth) * static_cast<std::size_t>(width - 1) + 1;
}

}  // namespace quiver
