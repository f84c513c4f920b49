// Binned SAH build (Wald 2007) of a binary tree over primitive boxes, split
// in place over an index array (so leaves are contiguous ranges), subtrees
// above a size threshold built in parallel with oneTBB; then the binary tree
// is collapsed into `width`-ary nodes by opening the child of largest area
// until the node is full (as Embree's BVH4/8 builders do). The result does
// not depend on the thread count: splits depend only on the input, and the
// wide nodes are laid out by a depth-first walk.
#include "geometry/bvh.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <limits>
#include <stdexcept>

#include <oneapi/tbb/parallel_invoke.h>

namespace quiver {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

struct BinaryNode {
  Box box;
  std::int32_t left = -1, right = -1;  // -1 for a leaf
  std::uint32_t first = 0, count = 0;  // leaf range in the index array
  bool leaf() const { return left < 0; }
};

class BinaryBuilder {
 public:
  BinaryBuilder(std::span<const Box> boxes, const BvhBuildOptions& options, std::vector<std::uint32_t>& ids)
      : boxes_(boxes), options_(options), ids_(ids), nodes_(2 * boxes.size()) {
    centroids_.reserve(boxes.size());
    for (const Box& b : boxes) centroids_.push_back(centroid(b));
  }

  std::int32_t build() { return build_range(0, static_cast<std::uint32_t>(ids_.size()), 1); }
  const std::vector<BinaryNode>& nodes() const { return nodes_; }

 private:
  struct Split {
    int axis = -1;
    float position = 0.f;  // centroids below go left
    float cost = kInf;
  };

  std::int32_t allocate() { return next_node_.fetch_add(1, std::memory_order_relaxed); }

  std::int32_t build_range(std::uint32_t begin, std::uint32_t end, int depth) {
    const std::int32_t index = allocate();
    BinaryNode& node = nodes_[index];
    Box box = empty_box(), centroid_box = empty_box();
    for (std::uint32_t i = begin; i < end; ++i) {
      grow(box, boxes_[ids_[i]]);
      grow(centroid_box, centroids_[ids_[i]]);
    }
    node.box = box;
    const std::uint32_t n = end - begin;
    const float leaf_cost = static_cast<float>(n);

    std::uint32_t middle = begin;
    if (depth < kSahDepthLimit) {
      const Split split = best_split(begin, end, box, centroid_box);
      const bool must_split = n > static_cast<std::uint32_t>(options_.max_leaf_size);
      if (!must_split && (split.axis < 0 || split.cost >= leaf_cost)) return make_leaf(node, begin, n);
      if (split.axis >= 0) {
        const auto below = [&](std::uint32_t id) { return centroids_[id][split.axis] < split.position; };
        middle = static_cast<std::uint32_t>(std::partition(ids_.begin() + begin, ids_.begin() + end, below) -
                                            ids_.begin());
      }
    } else if (n <= static_cast<std::uint32_t>(options_.max_leaf_size)) {
      return make_leaf(node, begin, n);
    }
    if (middle == begin || middle == end) middle = median_split(begin, end, centroid_box);

    std::int32_t left = -1, right = -1;
    if (n >= options_.parallel_threshold) {
      oneapi::tbb::parallel_invoke([&] { left = build_range(begin, middle, depth + 1); },
                                   [&] { right = build_range(middle, end, depth + 1); });
    } else {
      left = build_range(begin, middle, depth + 1);
      right = build_range(middle, end, depth + 1);
    }
    nodes_[index].left = left;
    nodes_[index].right = right;
    return index;
  }

  std::int32_t make_leaf(BinaryNode& node, std::uint32_t begin, std::uint32_t n) {
    node.first = begin;
    node.count = n;
    return static_cast<std::int32_t>(&node - nodes_.data());
  }

  // Object median along the widest centroid axis, ties by input index, so
  // equal centroids still split and the result is deterministic.
  std::uint32_t median_split(std::uint32_t begin, std::uint32_t end, const Box& centroid_box) {
    const Vec3<float> extent = centroid_box.hi - centroid_box.lo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    const std::uint32_t middle = begin + (end - begin) / 2;
    std::nth_element(ids_.begin() + begin, ids_.begin() + middle, ids_.begin() + end,
                     [&](std::uint32_t a, std::uint32_t b) {
                       const float ca = centroids_[a][axis], cb = centroids_[b][axis];
                       return ca < cb || (ca == cb && a < b);
                     });
    return middle;
  }

  // SAH over `bins` centroid bins per axis: cost = traversal + (A_L n_L + A_R n_R) / A.
  Split best_split(std::uint32_t begin, std::uint32_t end, const Box& box, const Box& centroid_box) const {
    constexpr int kMaxBins = 64;
    const int bins = std::clamp(options_.bins, 2, kMaxBins);
    const float area = half_area(box);
    Split best;
    if (!(area > 0.f)) return best;
    for (int axis = 0; axis < 3; ++axis) {
      const float lo = centroid_box.lo[axis], extent = centroid_box.hi[axis] - lo;
      if (!(extent > 0.f)) continue;
      const float scale = static_cast<float>(bins) / extent;
      std::array<Box, kMaxBins> bin_box;
      std::array<std::uint32_t, kMaxBins> bin_count{};
      bin_box.fill(empty_box());
      for (std::uint32_t i = begin; i < end; ++i) {
        const std::uint32_t id = ids_[i];
        const int b = std::min(bins - 1, static_cast<int>((centroids_[id][axis] - lo) * scale));
        grow(bin_box[b], boxes_[id]);
        ++bin_count[b];
      }
      // Sweep from the right: area and count of bins [b, bins).
      std::array<float, kMaxBins> right_area{};
      std::array<std::uint32_t, kMaxBins> right_count{};
      Box acc = empty_box();
      std::uint32_t count = 0;
      for (int b = bins - 1; b > 0; --b) {
        grow(acc, bin_box[b]);
        count += bin_count[b];
        right_area[b] = half_area(acc);
        right_count[b] = count;
      }
      acc = empty_box();
      count = 0;
      for (int b = 1; b < bins; ++b) {
        grow(acc, bin_box[b - 1]);
        count += bin_count[b - 1];
        if (count == 0 || right_count[b] == 0) continue;
        const float cost = options_.traversal_cost +
                           (half_area(acc) * static_cast<float>(count) +
                            right_area[b] * static_cast<float>(right_count[b])) / area;
        if (cost < best.cost) best = {axis, lo + static_cast<float>(b) / scale, cost};
      }
    }
    return best;
  }

  std::span<const Box> boxes_;
  const BvhBuildOptions& options_;
  std::vector<std::uint32_t>& ids_;
  std::vector<Vec3<float>> centroids_;
  std::vector<BinaryNode> nodes_;
  std::atomic<std::int32_t> next_node_{0};
};

// Writes the wide nodes depth first from the binary tree.
class Collapser {
 public:
  Collapser(const std::vector<BinaryNode>& nodes, Bvh& bvh) : nodes_(nodes), bvh_(bvh), width_(bvh.width) {}

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
    std::vector<std::int32_t> slots{nodes_[index].left, nodes_[index].right};
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
      slots[widest] = open.left;
      slots.insert(slots.begin() + widest + 1, open.right);
    }
    return slots;
  }

  std::int32_t write_node(const std::vector<std::int32_t>& slots, int depth) {
    const std::size_t index = bvh_.node_count++;
    const std::size_t w = static_cast<std::size_t>(width_);
    bvh_.nodes.resize(bvh_.node_count * bvh_.node_floats());
    float* block = bvh_.nodes.data() + index * bvh_.node_floats();
    bvh_.depth = std::max(bvh_.depth, depth);
    for (std::size_t s = 0; s < w; ++s) {
      Box box = empty_box();
      std::int32_t child = encode_leaf(0, 0);
      if (s < slots.size()) {
        const BinaryNode& n = nodes_[slots[s]];
        box = n.box;
        if (n.leaf()) child = encode_leaf(static_cast<std::int32_t>(n.first), static_cast<std::int32_t>(n.count));
      }
      for (int a = 0; a < 3; ++a) {
        block[static_cast<std::size_t>(a) * w + s] = box.lo[a];
        block[static_cast<std::size_t>(3 + a) * w + s] = box.hi[a];
      }
      block[6 * w + s] = std::bit_cast<float>(child);
    }
    for (std::size_t s = 0; s < slots.size(); ++s) {
      if (nodes_[slots[s]].leaf()) continue;
      const std::int32_t child = write_node(open_children(slots[s]), depth + 1);
      bvh_.nodes[index * bvh_.node_floats() + 6 * w + s] = std::bit_cast<float>(child);
    }
    return static_cast<std::int32_t>(index);
  }

  const std::vector<BinaryNode>& nodes_;
  Bvh& bvh_;
  int width_;
};

}  // namespace

Bvh build_bvh(std::span<const Box> boxes, const BvhBuildOptions& options, std::vector<std::uint32_t>& order) {
  if (options.width != 2 && options.width != 4 && options.width != 8) {
    throw std::invalid_argument("BVH width must be 2, 4 or 8");
  }
  if (options.max_leaf_size < 1 || options.max_leaf_size > kMaxLeafSize) {
    throw std::invalid_argument("BVH leaf size must be 1 to " + std::to_string(kMaxLeafSize));
  }
  if (boxes.size() > kMaxBvhPrimitives) {
    throw std::length_error("a BVH indexes at most 2^26 primitives per store");
  }
  order.resize(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) order[i] = static_cast<std::uint32_t>(i);
  Bvh bvh;
  if (boxes.empty()) return bvh;
  bvh.width = options.width;

  BinaryBuilder builder(boxes, options, order);
  const std::int32_t root = builder.build();
  bvh.bounds = builder.nodes()[root].box;
  Collapser(builder.nodes(), bvh).collapse_root(root);
  bvh.nodes.shrink_to_fit();
  return bvh;
}

}  // namespace quiver
