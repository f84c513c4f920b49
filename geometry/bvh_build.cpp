// Binned SAH build (Wald 2007) of a binary tree over primitive boxes, split
// in place over an array of (box, index) records (so leaves are contiguous
// ranges and every pass reads memory in order; one pass bins all three
// axes), subtrees above a size threshold built in parallel with oneTBB; then
// the binary tree is collapsed into `width`-ary nodes by opening the child
// of largest area until the node is full (as Embree's BVH4/8 builders do).
// The result does not depend on the thread count: splits depend only on the
// input, and the wide nodes are laid out by a depth-first walk. With two
// stores, a range that would become a leaf but holds both is split by store.
#include "geometry/bvh.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cstddef>
#include <functional>
#include <limits>
#include <memory>
#include <stdexcept>

#include <oneapi/tbb/parallel_invoke.h>

#include "geometry/parallel_indices.h"
#include "simd/lanes.h"

namespace quiver {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// No initializers: build_range sets both fields of the nodes it allocates,
// so the node array (up to 2n - 1 nodes) is not written twice. Children are
// allocated in pairs, so an inner node names only its left child.
struct BinaryNode {
  Box box;
  // Inner: the left child's index (the right child's is one more); leaf:
  // encode_leaf(first, count, store) of its range in the build order.
  std::int32_t link;
  bool leaf() const { return is_leaf(link); }
  std::int32_t left() const { return link; }
  std::int32_t right() const { return link + 1; }
};

// A primitive's box and input index. The build partitions these in place, so
// every pass over a node's range reads memory in order.
struct PrimRef {
  Box box;
  std::uint32_t id;
  float centroid(int axis) const { return quiver::centroid(box)[axis]; }
};
static_assert(offsetof(PrimRef, box.hi) == offsetof(PrimRef, box.lo) + 3 * sizeof(float));
static_assert(offsetof(PrimRef, id) == offsetof(PrimRef, box.hi) + 3 * sizeof(float));

// x, y, z and one lane that is never read (SSE2 is baseline x86-64).
using Lanes4 = xsimd::batch<float, xsimd::sse2>;

// A PrimRef's corners in 4 lanes: lane 3 of lo is hi.x, of hi the id's bits
// (at most 2^26: a finite float, never NaN).
inline Lanes4 lo_lanes(const PrimRef& r) { return Lanes4::load_unaligned(&r.box.lo.x); }
inline Lanes4 hi_lanes(const PrimRef& r) { return Lanes4::load_unaligned(&r.box.hi.x); }

// A SAH bin: its primitives' box, as lanes (min and max as in grow()). No
// initializers: best_split sets up only the bins it uses.
struct BinBox {
  Lanes4 lo, hi;
  static BinBox empty() { return {Lanes4(kInf), Lanes4(-kInf)}; }
  void grow(const Lanes4& box_lo, const Lanes4& box_hi) {
    lo = min(lo, box_lo);
    hi = max(hi, box_hi);
  }
  // half_area(box()) of a non-empty box, its extents subtracted in lanes.
  float half_area() const {
    alignas(16) float e[4];
    (hi - lo).store_aligned(e);
    return half_area_of_extent({e[0], e[1], e[2]});
  }
};

// The box of a range and the box of its centroids.
struct RangeBounds {
  Box box = empty_box(), centroids = empty_box();
};

class BinaryBuilder {
 public:
  BinaryBuilder(std::size_t count, const std::function<Box(std::size_t)>& box_of, const BvhBuildOptions& options,
                std::span<const std::uint8_t> store_of)
      : options_(options), store_of_(store_of), refs_(count), nodes_(new BinaryNode[2 * count]) {
    for_each_index(count, [&](std::size_t i) { refs_[i] = {box_of(i), static_cast<std::uint32_t>(i)}; });
  }

  std::int32_t build() {
    const auto n = static_cast<std::uint32_t>(refs_.size());
    const std::int32_t root = allocate(1);
    build_range(0, n, 1, bounds_of(0, n), root);
    return root;
  }
  const BinaryNode* nodes() const { return nodes_.get(); }
  // Frees the references once the order is written: the collapse reads only the nodes.
  void release_references() { std::vector<PrimRef>().swap(refs_); }
  // order[k]: the input index of the primitive at leaf position k.
  void write_order(std::vector<std::uint32_t>& order) const {
    for (std::size_t k = 0; k < refs_.size(); ++k) order[k] = refs_[k].id;
  }
  // store_position[k]: leaf position k counted within its store's primitives;
  // empty for one store (where it is k).
  std::vector<std::uint32_t> store_positions() const {
    if (store_of_.empty()) return {};
    std::vector<std::uint32_t> position(refs_.size());
    std::array<std::uint32_t, 2> next{};
    for (std::size_t k = 0; k < refs_.size(); ++k) position[k] = next[store(refs_[k])]++;
    return position;
  }

 private:
  struct Split {
    int axis = -1;
    float position = 0.f;  // centroids below go left
    float cost = kInf;
  };

  std::int32_t allocate(std::int32_t nodes) { return next_node_.fetch_add(nodes, std::memory_order_relaxed); }
  std::uint8_t store(const PrimRef& r) const { return store_of_.empty() ? 0 : store_of_[r.id]; }
  // The first position of store 1 after partitioning a range by store, or
  // `end` when the range holds one store only.
  std::uint32_t split_by_store(std::uint32_t begin, std::uint32_t end) {
    if (store_of_.empty()) return end;
    const auto in_store_0 = [&](const PrimRef& r) { return store(r) == 0; };
    const auto middle = std::partition(refs_.begin() + begin, refs_.begin() + end, in_store_0) - refs_.begin();
    return middle == begin ? end : static_cast<std::uint32_t>(middle);
  }

  RangeBounds bounds_of(std::uint32_t begin, std::uint32_t end) const {
    RangeBounds bounds;
    for (std::uint32_t i = begin; i < end; ++i) {
      const PrimRef& r = refs_[i];
      grow(bounds.box, r.box);
      grow(bounds.centroids, centroid(r.box));
    }
    return bounds;
  }

  // Builds the subtree of a range into the node at `index`.
  void build_range(std::uint32_t begin, std::uint32_t end, int depth, const RangeBounds& bounds, std::int32_t index) {
    BinaryNode& node = nodes_[index];
    node.box = bounds.box;
    const std::uint32_t n = end - begin;
    const float leaf_cost = static_cast<float>(n);

    std::uint32_t middle = begin;
    const bool fits_leaf = n <= static_cast<std::uint32_t>(options_.max_leaf_size);
    // Every split costs at least the traversal (the sum of a non-negative
    // term to it), so a range that fits a leaf and costs no more as one
    // is a leaf without binning: the tree best_split would have chosen.
    const bool leaf_at_least_as_cheap = fits_leaf && leaf_cost <= options_.traversal_cost;
    if (depth < kSahDepthLimit) {
      const Split split = leaf_at_least_as_cheap ? Split{} : best_split(begin, end, bounds);
      if (fits_leaf && (split.axis < 0 || split.cost >= leaf_cost)) {
        middle = split_by_store(begin, end);
        if (middle == end) return make_leaf(node, begin, n);
      } else if (split.axis >= 0) {
        const auto below = [&](const PrimRef& r) { return r.centroid(split.axis) < split.position; };
        middle = static_cast<std::uint32_t>(std::partition(refs_.begin() + begin, refs_.begin() + end, below) -
                                            refs_.begin());
      }
    } else if (fits_leaf) {
      middle = split_by_store(begin, end);
      if (middle == end) return make_leaf(node, begin, n);
    }
    if (middle == begin || middle == end) middle = median_split(begin, end, bounds.centroids);

    const std::int32_t left = allocate(2);
    node.link = left;
    if (n >= options_.parallel_threshold) {
      oneapi::tbb::parallel_invoke([&] { build_range(begin, middle, depth + 1, bounds_of(begin, middle), left); },
                                   [&] { build_range(middle, end, depth + 1, bounds_of(middle, end), left + 1); });
    } else {
      build_range(begin, middle, depth + 1, bounds_of(begin, middle), left);
      build_range(middle, end, depth + 1, bounds_of(middle, end), left + 1);
    }
  }

  void make_leaf(BinaryNode& node, std::uint32_t begin, std::uint32_t n) {
    node.link = encode_leaf(static_cast<std::int32_t>(begin), static_cast<std::int32_t>(n), store(refs_[begin]));
  }

  // Object median along the widest centroid axis, ties by input index, so
  // equal centroids still split and the result is deterministic.
  std::uint32_t median_split(std::uint32_t begin, std::uint32_t end, const Box& centroid_box) {
    const Vec3<float> extent = centroid_box.hi - centroid_box.lo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    const std::uint32_t middle = begin + (end - begin) / 2;
    std::nth_element(refs_.begin() + begin, refs_.begin() + middle, refs_.begin() + end,
                     [&](const PrimRef& a, const PrimRef& b) {
                       const float ca = a.centroid(axis), cb = b.centroid(axis);
                       return ca < cb || (ca == cb && a.id < b.id);
                     });
    return middle;
  }

  // SAH over `bins` centroid bins per axis, all three axes binned in one pass:
  // cost = traversal + (A_L n_L + A_R n_R) / A.
  Split best_split(std::uint32_t begin, std::uint32_t end, const RangeBounds& bounds) const {
    constexpr int kMaxBins = 64;
    const int bins = std::clamp(options_.bins, 2, kMaxBins);
    const float area = half_area(bounds.box);
    Split best;
    if (!(area > 0.f)) return best;
    alignas(16) std::array<float, 4> lo{}, scale{};
    std::array<bool, 3> binned{};
    for (int axis = 0; axis < 3; ++axis) {
      lo[axis] = bounds.centroids.lo[axis];
      const float extent = bounds.centroids.hi[axis] - lo[axis];
      binned[axis] = extent > 0.f;
      scale[axis] = binned[axis] ? static_cast<float>(bins) / extent : 0.f;
    }
    const Lanes4 lo_lanes4 = Lanes4::load_aligned(lo.data()), scale_lanes4 = Lanes4::load_aligned(scale.data());
    const auto last_bin = xsimd::batch<std::int32_t, xsimd::sse2>(bins - 1);
    std::array<std::array<BinBox, kMaxBins>, 3> bin_box;
    std::array<std::array<std::uint32_t, kMaxBins>, 3> bin_count;
    for (int axis = 0; axis < 3; ++axis) {
      std::fill_n(bin_box[axis].begin(), bins, BinBox::empty());
      std::fill_n(bin_count[axis].begin(), bins, 0u);
    }
    for (std::uint32_t i = begin; i < end; ++i) {
      const Lanes4 box_lo = lo_lanes(refs_[i]), box_hi = hi_lanes(refs_[i]);
      // The bin index on every axis at once, as centroid() and the scalar (int) cast give it.
      const Lanes4 position = (midpoint_of(box_lo, box_hi) - lo_lanes4) * scale_lanes4;
      alignas(16) std::array<std::int32_t, 4> bin;
      xsimd::min(xsimd::batch_cast<std::int32_t>(position), last_bin).store_aligned(bin.data());
      for (int axis = 0; axis < 3; ++axis) {
        if (!binned[axis]) continue;
        bin_box[axis][bin[axis]].grow(box_lo, box_hi);
        ++bin_count[axis][bin[axis]];
      }
    }
    for (int axis = 0; axis < 3; ++axis) {
      if (!binned[axis]) continue;
      // Candidate splits b (bins [0, b) left, [b, bins) right) cost the same
      // from just after one non-empty bin up to the next, and the first of
      // them wins a tie: only b = (a non-empty bin) + 1 is tried, with the
      // sweeps over the non-empty bins only (empty bins hold empty boxes).
      std::uint64_t filled = 0;
      for (int b = 0; b < bins; ++b) filled |= (bin_count[axis][b] != 0 ? 1ull : 0ull) << b;
      // From the right: area and count of bins [j, bins) at each non-empty j.
      std::array<float, kMaxBins> right_area;
      std::array<std::uint32_t, kMaxBins> right_count;
      BinBox acc = BinBox::empty();
      std::uint32_t count = 0;
      for (std::uint64_t rest = filled; rest != 0;) {
        const int j = 63 - std::countl_zero(rest);
        rest &= ~(1ull << j);
        acc.grow(bin_box[axis][j].lo, bin_box[axis][j].hi);
        count += bin_count[axis][j];
        right_area[j] = acc.half_area();
        right_count[j] = count;
      }
      acc = BinBox::empty();
      count = 0;
      for (std::uint64_t rest = filled; rest != 0;) {
        const int i = std::countr_zero(rest);
        rest &= rest - 1;
        acc.grow(bin_box[axis][i].lo, bin_box[axis][i].hi);
        count += bin_count[axis][i];
        if (rest == 0) break;  // nothing right of the last non-empty bin
        const int j = std::countr_zero(rest), b = i + 1;
        const float cost = options_.traversal_cost +
                           (acc.half_area() * static_cast<float>(count) +
                            right_area[j] * static_cast<float>(right_count[j])) / area;
        if (cost < best.cost) best = {axis, lo[axis] + static_cast<float>(b) / scale[axis], cost};
      }
    }
    return best;
  }

  const BvhBuildOptions& options_;
  std::span<const std::uint8_t> store_of_;
  std::vector<PrimRef> refs_;
  std::unique_ptr<BinaryNode[]> nodes_;
  std::atomic<std::int32_t> next_node_{0};
};

// Writes the wide nodes depth first from the binary tree.
class Collapser {
 public:
  Collapser(const BinaryNode* nodes, std::vector<std::uint32_t> store_position, Bvh& bvh)
      : nodes_(nodes), store_position_(std::move(store_position)), bvh_(bvh), width_(bvh.width) {}

  void collapse_root(std::int32_t root) {
    std::vector<std::int32_t> slots;
    if (nodes_[root].leaf()) {
      slots.push_back(root);
    } else {
      slots = open_children(root);
    }
    write_node(slots, 1);
  }

 private:
  // The binary node's children, opened by largest area until `width` slots.
  std::vector<std::int32_t> open_children(std::int32_t index) const {
    std::vector<std::int32_t> slots{nodes_[index].left(), nodes_[index].right()};
    while (static_cast<int>(slots.size()) < width_) {
      int widest = -1;
      float widest_area = -1.f;
      for (int s = 0; s < static_cast<int>(slots.size()); ++s) {
        const BinaryNode& n = nodes_[slots[s]];
        if (!n.leaf() && half_area(n.box) > widest_area) {
          widest = s;
          widest_area = half_area(n.box);
        }
      }
      if (widest < 0) break;
      const BinaryNode& open = nodes_[slots[widest]];
      slots[widest] = open.left();
      slots.insert(slots.begin() + widest + 1, open.right());
    }
    return slots;
  }

  // Returns the node's child-slot value (its block's float offset).
  std::int32_t write_node(const std::vector<std::int32_t>& slots, int depth) {
    const std::size_t index = bvh_.node_count++;
    const std::size_t w = static_cast<std::size_t>(width_);
    if ((index + 1) * bvh_.node_floats() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())) {
      throw std::length_error("BVH nodes exceed 2^31 floats");
    }
    bvh_.nodes.resize(bvh_.node_count * bvh_.node_floats());
    float* block = bvh_.nodes.data() + index * bvh_.node_floats();
    bvh_.depth = std::max(bvh_.depth, depth);
    for (std::size_t s = 0; s < w; ++s) {
      Box box = empty_box();
      std::int32_t child = encode_leaf(0, 0);
      if (s < slots.size()) {
        const BinaryNode& n = nodes_[slots[s]];
        box = n.box;
        if (n.leaf()) child = leaf_in_its_store(n.link);
      }
      for (int a = 0; a < 3; ++a) {
        block[static_cast<std::size_t>(a) * w + s] = box.lo[a];
        block[static_cast<std::size_t>(3 + a) * w + s] = box.hi[a];
      }
      block[child_slot(w, static_cast<int>(s))] = std::bit_cast<float>(child);
    }
    for (std::size_t s = 0; s < slots.size(); ++s) {
      if (nodes_[slots[s]].leaf()) continue;
      const std::int32_t child = write_node(open_children(slots[s]), depth + 1);
      bvh_.nodes[index * bvh_.node_floats() + child_slot(w, static_cast<int>(s))] = std::bit_cast<float>(child);
    }
    return static_cast<std::int32_t>(index * bvh_.node_floats());
  }

  // A leaf's range renumbered within its store's primitives.
  std::int32_t leaf_in_its_store(std::int32_t leaf) const {
    if (store_position_.empty()) return leaf;
    const auto first = static_cast<std::size_t>(leaf_first(leaf));
    return encode_leaf(static_cast<std::int32_t>(store_position_[first]), leaf_count(leaf), leaf_store(leaf));
  }

  const BinaryNode* nodes_;
  std::vector<std::uint32_t> store_position_;
  Bvh& bvh_;
  int width_;
};

}  // namespace

Bvh build_bvh(std::span<const Box> boxes, const BvhBuildOptions& options, std::vector<std::uint32_t>& order,
              std::span<const std::uint8_t> store_of) {
  return build_bvh(boxes.size(), [&](std::size_t i) { return boxes[i]; }, options, order, store_of);
}

Bvh build_bvh(std::size_t count, const std::function<Box(std::size_t)>& box_of, const BvhBuildOptions& options,
              std::vector<std::uint32_t>& order, std::span<const std::uint8_t> store_of) {
  if (options.width != 2 && options.width != 4 && options.width != 8) {
    throw std::invalid_argument("BVH width must be 2, 4 or 8");
  }
  if (options.max_leaf_size < 1 || options.max_leaf_size > kMaxLeafSize) {
    throw std::invalid_argument("BVH leaf size must be 1 to " + std::to_string(kMaxLeafSize));
  }
  if (count > kMaxBvhPrimitives) {
    throw std::length_error("a BVH indexes at most 2^26 primitives");
  }
  if (!store_of.empty() && store_of.size() != count) {
    throw std::invalid_argument("BVH store list and box list differ in length");
  }
  if (std::any_of(store_of.begin(), store_of.end(), [](std::uint8_t s) { return s > 1; })) {
    throw std::invalid_argument("a BVH indexes stores 0 and 1 only");
  }
  order.resize(count);
  Bvh bvh;
  if (count == 0) return bvh;
  bvh.width = options.width;

  BinaryBuilder builder(count, box_of, options, store_of);
  const std::int32_t root = builder.build();
  builder.write_order(order);
  std::vector<std::uint32_t> store_positions = builder.store_positions();
  builder.release_references();
  bvh.bounds = builder.nodes()[root].box;
  Collapser(builder.nodes(), std::move(store_positions), bvh).collapse_root(root);
  bvh.nodes.shrink_to_fit();
  return bvh;
}

}  // namespace quiver
