// BVH build invariants, and traversal against the brute-force scan: for every
// kernel unit, node width, and traversal (packets, single rays, automatic),
// closest hits equal the scalar unit's scan of the same store bit for bit,
// and any-hit answers equal too.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <span>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>
#include <oneapi/tbb/task_arena.h>

#include "geometry/bvh.h"
#include "geometry/bvh_store.h"
#include "geometry/kind_streams.h"
#include "geometry/primitive_bounds.h"
#include "tests/support/kernel_checks.h"
#include "tests/support/ray_sampling.h"
#include "tests/support/study_streams.h"

namespace quiver {
namespace {

using testing::RaySampler;

std::vector<Box> random_boxes(RaySampler& s, std::size_t n) {
  std::vector<Box> boxes;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3<float> c = s.in_box({-10, -10, -10}, {10, 10, 10});
    const Vec3<float> e{s.uniform(0.f, 0.5f), s.uniform(0.f, 0.5f), s.uniform(0.f, 0.5f)};
    boxes.push_back({c - e, c + e});
  }
  return boxes;
}

// Equal as stored: node arrays hold child slots as float bits.
bool same_bits(float a, float b) { return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b); }

bool contains(const Box& outer, const Box& inner) {
  for (int a = 0; a < 3; ++a) {
    if (!(outer.lo[a] <= inner.lo[a] && inner.hi[a] <= outer.hi[a])) return false;
  }
  return true;
}

Box child_box(const Bvh& bvh, std::size_t node, int c) {
  const std::size_t w = static_cast<std::size_t>(bvh.width);
  const float* b = bvh.boxes(node) + static_cast<std::size_t>(c);
  return {{b[0 * w], b[1 * w], b[2 * w]}, {b[3 * w], b[4 * w], b[5 * w]}};
}

// The positions in `order` of each store's primitives, in order: a leaf of
// store s at local position k holds the primitive at order[positions[s][k]].
std::array<std::vector<std::uint32_t>, 2> store_positions(const std::vector<std::uint32_t>& order,
                                                          const std::vector<std::uint8_t>& store_of) {
  std::array<std::vector<std::uint32_t>, 2> positions;
  for (std::uint32_t k = 0; k < order.size(); ++k) positions[store_of.empty() ? 0 : store_of[order[k]]].push_back(k);
  return positions;
}

// Walks the tree: every child box contains the boxes of the primitives under
// it; counts how often each position of `order` is reached.
void check_subtree(const Bvh& bvh, std::size_t node, const std::vector<Box>& boxes,
                   const std::vector<std::uint32_t>& order, const std::array<std::vector<std::uint32_t>, 2>& positions,
                   std::vector<int>& reached, int max_leaf, int depth) {
  ASSERT_LE(depth, bvh.depth);
  for (int c = 0; c < bvh.width; ++c) {
    const std::int32_t child = bvh.child(node, c);
    const Box box = child_box(bvh, node, c);
    if (is_leaf(child)) {
      ASSERT_LE(leaf_count(child), max_leaf);
      const std::vector<std::uint32_t>& in_store = positions[static_cast<std::size_t>(leaf_store(child))];
      for (std::int32_t k = leaf_first(child); k < leaf_first(child) + leaf_count(child); ++k) {
        const std::uint32_t position = in_store.at(static_cast<std::size_t>(k));
        ++reached.at(position);
        EXPECT_TRUE(contains(box, boxes[order[position]])) << "position " << position;
      }
      continue;
    }
    ASSERT_EQ(static_cast<std::size_t>(child) % bvh.node_floats(), 0u);  // a block's offset
    ASSERT_LT(bvh.node_of(child), bvh.node_count);
    ASSERT_GT(bvh.node_of(child), node);  // depth-first layout: no cycles
    check_subtree(bvh, bvh.node_of(child), boxes, order, positions, reached, max_leaf, depth + 1);
  }
}

// store_of empty: one store.
void expect_valid_bvh(const std::vector<Box>& boxes, const BvhBuildOptions& options,
                      const std::vector<std::uint8_t>& store_of = {}) {
  std::vector<std::uint32_t> order;
  const Bvh bvh = build_bvh(boxes, options, order, store_of);
  ASSERT_EQ(order.size(), boxes.size());
  ASSERT_EQ(bvh.width, options.width);
  ASSERT_LE(bvh.depth, kMaxBvhDepth);
  ASSERT_EQ(bvh.nodes.size(), bvh.node_count * 7 * static_cast<std::size_t>(options.width));
  std::vector<int> reached(boxes.size(), 0);
  check_subtree(bvh, 0, boxes, order, store_positions(order, store_of), reached, options.max_leaf_size, 1);
  for (std::size_t k = 0; k < reached.size(); ++k) ASSERT_EQ(reached[k], 1) << "position " << k;
  std::vector<std::uint32_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t k = 0; k < sorted.size(); ++k) ASSERT_EQ(sorted[k], k);  // a permutation
}

TEST(BvhBuild, EveryPrimitiveInOneLeafInsideEveryBoxAboveIt) {
  RaySampler s(11);
  for (int width : {2, 4, 8}) {
    for (std::size_t n : {1u, 7u, 9u, 100u, 5000u}) {
      SCOPED_TRACE(::testing::Message() << "width " << width << ", " << n << " boxes");
      BvhBuildOptions options;
      options.width = width;
      options.parallel_threshold = 256;  // exercise the parallel build
      expect_valid_bvh(random_boxes(s, n), options);
    }
  }
}

// Leaves hold one store each (a leaf's range is counted in its own store),
// however the stores interleave, down to identical boxes in both.
TEST(BvhBuild, TwoStoresLeavesHoldOneStoreEach) {
  RaySampler s(12);
  for (int width : {2, 4, 8}) {
    for (std::size_t n : {2u, 9u, 100u, 5000u}) {
      SCOPED_TRACE(::testing::Message() << "width " << width << ", " << n << " boxes");
      BvhBuildOptions options;
      options.width = width;
      options.parallel_threshold = 256;
      std::vector<Box> boxes = random_boxes(s, n);
      std::vector<std::uint8_t> store_of(n);
      for (std::size_t i = 0; i < n; ++i) store_of[i] = s.uniform(0.f, 1.f) < 0.3f ? 1 : 0;
      expect_valid_bvh(boxes, options, store_of);
      const std::vector<Box> same(n, boxes[0]);
      expect_valid_bvh(same, options, store_of);
    }
  }
}

TEST(BvhBuild, OneStoreAsTwoGivesTheSameTree) {
  RaySampler s(14);
  const std::vector<Box> boxes = random_boxes(s, 3000);
  std::vector<std::uint32_t> one_order, two_order;
  const Bvh one = build_bvh(boxes, BvhBuildOptions{}, one_order);
  const Bvh two = build_bvh(boxes, BvhBuildOptions{}, two_order, std::vector<std::uint8_t>(boxes.size(), 0));
  EXPECT_EQ(one_order, two_order);
  ASSERT_EQ(one.nodes.size(), two.nodes.size());
  EXPECT_TRUE(std::equal(one.nodes.begin(), one.nodes.end(), two.nodes.begin(), two.nodes.end(), same_bits));
}

TEST(BvhBuild, IdenticalBoxesStillSplitIntoSmallLeaves) {
  const std::vector<Box> boxes(5000, Box{{1, 2, 3}, {1.5f, 2.5f, 3.5f}});
  BvhBuildOptions options;
  options.max_leaf_size = 4;
  expect_valid_bvh(boxes, options);
}

TEST(BvhBuild, ExponentiallySpacedBoxesStayWithinTheDepthLimit) {
  // SAH peels one box per level here; past kSahDepthLimit the median split takes over.
  std::vector<Box> boxes;
  for (int i = 0; i < 120; ++i) {
    const float x = std::ldexp(1.f, i - 60);
    boxes.push_back({{x, 0, 0}, {x * 1.01f, 1, 1}});
  }
  BvhBuildOptions options;
  options.max_leaf_size = 1;
  options.width = 2;
  expect_valid_bvh(boxes, options);
}

TEST(BvhBuild, GrowingByAnEmptyBoxChangesNothing) {
  const Box box{{1, 2, 3}, {4, 5, 6}};
  Box grown = box;
  grow(grown, empty_box());
  Box from_empty = empty_box();
  grow(from_empty, box);
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(grown.lo[a], box.lo[a]);
    EXPECT_EQ(grown.hi[a], box.hi[a]);
    EXPECT_EQ(from_empty.lo[a], box.lo[a]);
    EXPECT_EQ(from_empty.hi[a], box.hi[a]);
  }
}

// Two clusters far apart along x leave empty SAH bins between them on that
// axis; the root split must still separate them there. (A bin sweep that
// lets an empty bin's inverted box into its running union gets infinite
// areas on that axis and splits along y, where the clusters interleave.)
TEST(BvhBuild, SahSplitsAcrossEmptyBins) {
  std::vector<Box> boxes;
  for (int i = 0; i < 16; ++i) {
    const float x = i < 4 ? 0.f : 100.f;
    const float y = static_cast<float>((i * 5) % 16) / 16.f;
    boxes.push_back({{x, y, 0}, {x + 1, y + 0.05f, 1}});
  }
  BvhBuildOptions options;
  options.width = 2;  // the root's children are the first split's sides
  std::vector<std::uint32_t> order;
  const Bvh bvh = build_bvh(boxes, options, order);
  for (int c = 0; c < 2; ++c) {
    const Box box = child_box(bvh, 0, c);
    EXPECT_EQ(box.hi.x - box.lo.x, 1.f) << "root child " << c << " spans both clusters";
  }
}

// The number of primitives in the subtree of a child slot.
std::size_t primitives_under(const Bvh& bvh, std::size_t node, int c) {
  const std::int32_t child = bvh.child(node, c);
  if (is_leaf(child)) return static_cast<std::size_t>(leaf_count(child));
  std::size_t count = 0;
  for (int k = 0; k < bvh.width; ++k) count += primitives_under(bvh, bvh.node_of(child), k);
  return count;
}

// The root's split (a 2-wide tree's two children) costs no more, by the SAH,
// than any split at a bin boundary of the centroids on any axis, counted
// and bounded here independently of the builder's bin sweeps.
TEST(BvhBuild, RootSplitHasTheLeastSahCostOfEveryBinBoundary) {
  RaySampler s(11);
  const std::vector<Box> boxes = random_boxes(s, 1000);
  BvhBuildOptions options;
  options.width = 2;
  std::vector<std::uint32_t> order;
  const Bvh bvh = build_bvh(boxes, options, order);
  const double root_area = half_area(bvh.bounds);
  const auto cost = [&](const Box& left, std::size_t n_left, const Box& right, std::size_t n_right) {
    return options.traversal_cost +
           (double(half_area(left)) * double(n_left) + double(half_area(right)) * double(n_right)) / root_area;
  };
  const double built = cost(child_box(bvh, 0, 0), primitives_under(bvh, 0, 0), child_box(bvh, 0, 1),
                            primitives_under(bvh, 0, 1));
  Box centroids = empty_box();
  for (const Box& b : boxes) grow(centroids, centroid(b));
  double least = std::numeric_limits<double>::infinity();
  for (int axis = 0; axis < 3; ++axis) {
    const float lo = centroids.lo[axis], extent = centroids.hi[axis] - lo;
    for (int boundary = 1; boundary < options.bins; ++boundary) {
      Box left = empty_box(), right = empty_box();
      std::size_t n_left = 0;
      for (const Box& b : boxes) {
        const int bin = std::min(static_cast<int>((centroid(b)[axis] - lo) * (float(options.bins) / extent)),
                                 options.bins - 1);
        if (bin < boundary) {
          grow(left, b);
          ++n_left;
        } else {
          grow(right, b);
        }
      }
      if (n_left > 0 && n_left < boxes.size()) {
        least = std::min(least, cost(left, n_left, right, boxes.size() - n_left));
      }
    }
  }
  EXPECT_LE(built, least * (1.0 + 1e-5)) << "the root split costs " << built << ", a bin boundary " << least;
}

TEST(BvhBuild, SameTreeForAnyThreadCount) {
  RaySampler s(5);
  const std::vector<Box> boxes = random_boxes(s, 20000);
  BvhBuildOptions options;
  options.parallel_threshold = 64;
  auto build_with = [&](int threads, std::vector<std::uint32_t>& order) {
    oneapi::tbb::task_arena arena(threads);
    return arena.execute([&] { return build_bvh(boxes, options, order); });
  };
  std::vector<std::uint32_t> order1, order2;
  const Bvh one = build_with(1, order1), two = build_with(2, order2);
  EXPECT_EQ(order1, order2);
  EXPECT_EQ(one.node_count, two.node_count);
  EXPECT_TRUE(std::equal(one.nodes.begin(), one.nodes.end(), two.nodes.begin(), two.nodes.end(), same_bits));
}

TEST(BvhBuild, RejectsBadOptionsAndEmptyInputGivesNoTree) {
  std::vector<std::uint32_t> order;
  const std::vector<Box> one{Box{{0, 0, 0}, {1, 1, 1}}};
  BvhBuildOptions bad_width;
  bad_width.width = 3;
  EXPECT_THROW(build_bvh(one, bad_width, order), std::invalid_argument);
  BvhBuildOptions bad_leaf;
  bad_leaf.max_leaf_size = kMaxLeafSize + 1;
  EXPECT_THROW(build_bvh(one, bad_leaf, order), std::invalid_argument);
  bad_leaf.max_leaf_size = 0;
  EXPECT_THROW(build_bvh(one, bad_leaf, order), std::invalid_argument);
  for (const int ends : {1, int(kMaxLeafSize)}) {  // both ends of the range are leaf sizes
    BvhBuildOptions leaf;
    leaf.max_leaf_size = ends;
    EXPECT_FALSE(build_bvh(one, leaf, order).empty()) << ends;
  }
  EXPECT_TRUE(build_bvh(std::vector<Box>{}, BvhBuildOptions{}, order).empty());
  EXPECT_THROW(build_bvh(one, BvhBuildOptions{}, order, std::vector<std::uint8_t>{2}), std::invalid_argument);
  EXPECT_THROW(build_bvh(one, BvhBuildOptions{}, order, std::vector<std::uint8_t>{0, 1}), std::invalid_argument);
}

// ---- traversal vs brute force ---------------------------------------------------

// A scene per kind: random primitives (some duplicated, so hits tie exactly)
// in [-10, 10]^3.
template <class Desc>
void add_duplicates(RaySampler& s, std::vector<Desc>& out, int n) {
  for (int i = 0; i < n / 10; ++i) out.push_back(out[static_cast<std::size_t>(s.uniform_int(0, n - 1))]);
}

std::vector<SphereDesc> random_spheres(RaySampler& s, int n) {
  std::vector<SphereDesc> out;
  for (int i = 0; i < n; ++i) out.push_back({s.in_box({-10, -10, -10}, {10, 10, 10}), s.uniform(0.05f, 1.f)});
  add_duplicates(s, out, n);
  return out;
}

std::vector<TriangleDesc> random_triangles(RaySampler& s, int n) {
  std::vector<TriangleDesc> out;
  for (int i = 0; i < n; ++i) {
    const Vec3<float> c = s.in_box({-10, -10, -10}, {10, 10, 10});
    TriangleDesc t;
    for (auto& p : t.p) p = c + s.unit_direction() * s.uniform(0.2f, 2.f);
    out.push_back(t);
  }
  // Neighbours sharing an edge, and exact duplicates.
  for (int i = 0; i < n / 5; ++i) {
    TriangleDesc t = out[static_cast<std::size_t>(i)];
    t.p[2] = t.p[0] + t.p[1] - t.p[2];
    out.push_back(t);
  }
  add_duplicates(s, out, n);
  return out;
}

std::vector<PolygonDesc> random_polygons(RaySampler& s, int n) {
  std::vector<PolygonDesc> out;
  for (int i = 0; i < n; ++i) {
    // A star (concave) in a random plane.
    const Vec3<float> c = s.in_box({-10, -10, -10}, {10, 10, 10});
    const Vec3<float> u = normalize(s.unit_direction());
    const Vec3<float> v = normalize(cross(u, s.unit_direction()));
    const int points = s.uniform_int(3, 7);
    PolygonDesc p;
    for (int k = 0; k < 2 * points; ++k) {
      const float angle = std::numbers::pi_v<float> * static_cast<float>(k) / static_cast<float>(points);
      const float radius = (k % 2 == 0 ? 1.5f : 0.6f) * s.uniform(0.5f, 1.f);
      p.vertices.push_back(c + u * (radius * std::cos(angle)) + v * (radius * std::sin(angle)));
    }
    out.push_back(p);
  }
  return out;
}

// A store put in leaf order by gathering its columns equals, column by
// column and in memory held per column, the store its builder makes from
// the inputs in that order (what it replaced: a second build).
template <class Desc, class Builder>
void expect_gather_equals_rebuild(const std::vector<Desc>& descs, Builder builder) {
  BuildReport report;
  auto store = builder(std::span<const Desc>(descs), report);
  ASSERT_LT(store.count, descs.size());  // some dropped: positions and input indices differ
  BvhBuildOptions options;
  const Bvh bvh = reorder_for_bvh(DescRefs<Desc>(descs), builder, options, store);
  ASSERT_FALSE(bvh.empty());
  std::vector<Desc> in_leaf_order;
  for (std::uint32_t i : store.source) in_leaf_order.push_back(descs[i]);
  const auto rebuilt = builder(std::span<const Desc>(in_leaf_order), report);
  ASSERT_EQ(rebuilt.count, store.count);
  const auto gathered_columns = store.columns();
  const auto rebuilt_columns = rebuilt.columns();
  for (std::size_t c = 0; c < gathered_columns.size(); ++c) {
    const AlignedFloats& a = *gathered_columns[c];
    const AlignedFloats& b = *rebuilt_columns[c];
    ASSERT_EQ(a.size(), b.size()) << "column " << c;
    EXPECT_EQ(bytes_of(a), bytes_of(b)) << "column " << c;  // no room held beyond the padding
    for (std::size_t k = 0; k < a.size(); ++k) {
      ASSERT_TRUE(same_bits(a[k], b[k])) << "column " << c << ", primitive " << k;
    }
  }
  EXPECT_EQ(store.source.capacity(), store.count);
}

TEST(BvhStore, GatheredStoresEqualStoresBuiltInLeafOrder) {
  RaySampler s(31);
  std::vector<TriangleDesc> triangles = random_triangles(s, 300);
  for (std::size_t i = 0; i < triangles.size(); i += 3) {  // some with normals and uvs: the others get defaults
    triangles[i].normals = {{s.unit_direction(), s.unit_direction(), s.unit_direction()}};
    triangles[i].uvs = {{{0.1f, 0.2f}, {0.9f, 0.2f}, {0.5f, 0.8f}}};
  }
  triangles[5].p[1] = triangles[5].p[0];  // degenerate: dropped
  expect_gather_equals_rebuild(triangles, build_triangles);
  std::vector<SphereDesc> spheres = random_spheres(s, 300);
  spheres[7].radius = -1.f;  // dropped
  expect_gather_equals_rebuild(spheres, build_spheres);
}

TEST(PrimitiveBounds, SpheresAndPolygonsLieInsideTheirBoxesInExactArithmetic) {
  // Sphere extents c +- sqrt(r^2) (the kernels use r^2) and the corners of
  // stored polygons (projected vertices lifted onto the stored plane), in
  // double, against boxes computed with float rounding.
  RaySampler s(3);
  std::vector<SphereDesc> sphere_descs;
  for (int i = 0; i < 2000; ++i) {
    sphere_descs.push_back({s.in_box({-1e4f, -1e4f, -1e4f}, {1e4f, 1e4f, 1e4f}), s.uniform(1e-3f, 10.f)});
  }
  BuildReport report;
  const SphereSoA spheres = build_spheres(sphere_descs, report);
  for (std::size_t i = 0; i < spheres.count; ++i) {
    const Box box = primitive_box(spheres, i);
    const double c[3] = {spheres.cx[i], spheres.cy[i], spheres.cz[i]};
    const double r = std::sqrt(static_cast<double>(spheres.r2[i]));
    for (int a = 0; a < 3; ++a) {
      ASSERT_LE(static_cast<double>(box.lo[a]), c[a] - r) << "sphere " << i;
      ASSERT_GE(static_cast<double>(box.hi[a]), c[a] + r) << "sphere " << i;
    }
  }
  const std::vector<PolygonDesc> polygon_descs = random_polygons(s, 500);
  const PolygonSoA polygons = build_polygons(polygon_descs, report);
  for (std::size_t i = 0; i < polygons.count; ++i) {
    const Box box = primitive_box(polygons, i);
    const int au = polygons.axis_u[i], av = polygons.axis_v[i], ak = 3 - au - av;
    const double n[3] = {polygons.nx[i], polygons.ny[i], polygons.nz[i]};
    for (std::int32_t k = 0; k < polygons.vertex_count[i]; ++k) {
      double p[3];
      p[au] = static_cast<double>(polygons.origin_u[i]) + polygons.pu[polygons.first_vertex[i] + k];
      p[av] = static_cast<double>(polygons.origin_v[i]) + polygons.pv[polygons.first_vertex[i] + k];
      const std::size_t first = polygons.first_vertex[i];
      const double v0k = ak == 0 ? polygons.px[first] : (ak == 1 ? polygons.py[first] : polygons.pz[first]);
      p[ak] = v0k - (n[au] * polygons.pu[first + k] + n[av] * polygons.pv[first + k]) / n[ak];
      for (int a = 0; a < 3; ++a) {
        ASSERT_LE(static_cast<double>(box.lo[a]), p[a]) << "polygon " << i;
        ASSERT_GE(static_cast<double>(box.hi[a]), p[a]) << "polygon " << i;
      }
    }
  }
}

std::vector<ConeDesc> random_cones(RaySampler& s, int n) {
  std::vector<ConeDesc> out;
  for (int i = 0; i < n; ++i) {
    const Vec3<float> b = s.in_box({-10, -10, -10}, {10, 10, 10});
    const float r0 = s.uniform(0.1f, 0.8f);
    const float r1 = i % 2 == 0 ? r0 : s.uniform(0.f, 0.8f);  // cylinders and cones
    out.push_back({b, r0, b + s.unit_direction() * s.uniform(0.5f, 3.f), r1});
  }
  return out;
}

// The rays as SoA, their padding lanes poisoned (NaN, inf).
RaySoA padded_soa(const std::vector<Ray<float>>& rays) {
  RaySoA soa = testing::to_soa(rays);
  testing::poison_padding(soa);
  return soa;
}

// Coherent camera rays (one eye, a grid of directions), random rays from
// inside the scene, and adversarial ones (NaN, Inf, empty intervals).
RaySoA traversal_rays(RaySampler& s) {
  std::vector<Ray<float>> rays;
  const Vec3<float> eye{0.5f, 1.f, -30.f};
  for (int j = 0; j < 61; ++j) {
    for (int i = 0; i < 61; ++i) {
      const Vec3<float> target{-12.f + 0.4f * static_cast<float>(i), -12.f + 0.4f * static_cast<float>(j), 0.f};
      rays.push_back(s.toward(eye, target));
    }
  }
  for (int i = 0; i < 3000; ++i) {
    Ray<float> r{s.in_box({-11, -11, -11}, {11, 11, 11}), s.unit_direction(), 0.f,
                 std::numeric_limits<float>::infinity()};
    if (i % 3 == 0) r.tmax = s.uniform(0.5f, 10.f);
    rays.push_back(r);
  }
  // Packets whose lanes share an octant but not an origin (the frustum's
  // intervals): toward one point outside the scene (shadow rays, t in (0, 1),
  // some starting inside primitives' boxes), and parallel rays along z with
  // +0 and -0 in x and y (1/d = +-inf).
  const Vec3<float> light{30.f, 25.f, -20.f};
  for (int i = 0; i < 800; ++i) {
    const Vec3<float> from = s.in_box({-11, -11, -11}, {11, 11, 11});
    rays.push_back({from, light - from, i % 2 == 0 ? 0.f : s.uniform(0.f, 0.2f), 1.f});
  }
  for (int j = 0; j < 40; ++j) {
    for (int i = 0; i < 40; ++i) {
      const float zero = j < 20 ? 0.f : -0.f;
      rays.push_back({{-12.f + 0.6f * static_cast<float>(i), -12.f + 0.6f * static_cast<float>(j), -30.f},
                      {zero, zero, 1.f}, 0.f, std::numeric_limits<float>::infinity()});
    }
  }
  // Coherent packets (one origin, one octant) with a NaN tmax beside +inf
  // and short ones: a NaN lane must not hide another lane's tmax from the
  // frustum (the pattern defeats a min/max reduction that drops NaN).
  while (rays.size() % 8 != 0) rays.push_back(s.toward(eye, {0.f, 0.f, 0.f}));
  const float tmax_pattern[4] = {std::numeric_limits<float>::infinity(), 0.5f,
                                 std::numeric_limits<float>::quiet_NaN(), 0.5f};
  for (int i = 0; i < 512; ++i) {
    const float x = 2.f + 0.5f * static_cast<float>(i % 16), y = 2.f + 0.25f * static_cast<float>(i / 16);
    Ray<float> r = s.toward(eye, {x, y, 0.f});
    r.tmax = tmax_pattern[i % 4];
    rays.push_back(r);
  }
  for (const Ray<float>& r : testing::adversarial_rays(s, 500, {0, 0, 0}, 10.f)) rays.push_back(r);
  return padded_soa(rays);
}

// Closest and any hits through the tree (`stores`: one store, or the
// tested stores of a tree over two) equal `expected` for every traversal.
template <class S, class Stores>
void expect_every_traversal_gives(const BvhStreams<S>& tree, const Stores& stores, const Bvh& bvh,
                                  const RaySoA& rays, const HitSoA& expected, const OcclusionSoA& expected_occlusion) {
  for (BvhTraversal traversal : {BvhTraversal::automatic, BvhTraversal::packets, BvhTraversal::single}) {
    SCOPED_TRACE(::testing::Message() << "traversal " << static_cast<int>(traversal));
    HitSoA hits(rays);
    OcclusionSoA occlusion(rays);
    tree.closest_hits(rays, stores, bvh, hits, traversal);
    tree.any_hits(rays, stores, bvh, occlusion, traversal);
    EXPECT_TRUE(testing::hits_bit_equal(expected, hits));
    EXPECT_TRUE(testing::occlusion_equal(expected_occlusion, occlusion));
  }
}

template <class S>
void expect_bvh_matches_scan(const KernelStreams<S>& scan, const BvhStreams<S>& tree, const S& store, const Bvh& bvh,
                             const RaySoA& rays) {
  HitSoA expected(rays);
  OcclusionSoA expected_occlusion(rays);
  scan.closest_packets(rays, store, expected);
  scan.occluded_packets(rays, store, expected_occlusion);
  ASSERT_GT(expected.hit_count(), rays.count / 10);  // the scene is hit
  expect_every_traversal_gives(tree, store, bvh, rays, expected, expected_occlusion);
}

// One BVH over two stores (ids not overlapping): for each set of tested
// stores, closest and any hits equal the scans of those stores.
template <class S>
void expect_two_store_bvh_matches_scan(const KernelStreams<S>& scan, const BvhStreams<S>& tree, const S& first,
                                       const S& second, const Bvh& bvh, const RaySoA& rays) {
  for (unsigned tested : {1u, 2u, 3u}) {
    SCOPED_TRACE(::testing::Message() << "tested stores " << tested);
    HitSoA expected(rays);
    OcclusionSoA expected_occlusion(rays);
    for (unsigned s = 0; s < 2; ++s) {
      if (((tested >> s) & 1u) == 0) continue;
      scan.closest_packets(rays, s == 0 ? first : second, expected);
      scan.occluded_packets(rays, s == 0 ? first : second, expected_occlusion);
    }
    ASSERT_GT(expected.hit_count(), rays.count / 20);
    const BvhStores<S, 2> stores{{&first, &second}, tested};
    expect_every_traversal_gives(tree, stores, bvh, rays, expected, expected_occlusion);
  }
}

// Builds the kind's store in BVH order for each node width and compares;
// then the even and odd descs as two stores under one BVH. The study walks
// a method the product leaves out at the product's node width only.
template <KernelUnit U, class Desc, class Builder, class Scan, class Tree>
void check_kind(const std::vector<Desc>& descs, Builder builder, const Scan& scan, const Tree& tree,
                const RaySoA& rays, std::span<const int> widths = kStudyNodeWidths) {
  std::array<std::vector<Desc>, 2> halves;
  for (std::size_t i = 0; i < descs.size(); ++i) halves[i % 2].push_back(descs[i]);
  for (int width : widths) {
    SCOPED_TRACE(::testing::Message() << "node width " << width);
    BuildReport report;
    auto store = builder(std::span<const Desc>(descs), report);
    BvhBuildOptions options;
    options.width = width;
    options.max_leaf_size = width == 2 ? 3 : 8;
    const Bvh bvh = reorder_for_bvh(DescRefs<Desc>(descs), builder, options, store);
    ASSERT_FALSE(bvh.empty());
    expect_bvh_matches_scan(scan, tree, store, bvh, rays);

    auto first = builder(std::span<const Desc>(halves[0]), report);
    auto second = builder(std::span<const Desc>(halves[1]), report);
    const Bvh shared = reorder_for_bvh(DescRefs<Desc>(halves[0]), first, DescRefs<Desc>(halves[1]),
                                       second, builder, options);
    second.id_base = static_cast<std::int32_t>(first.count);
    expect_two_store_bvh_matches_scan(scan, tree, first, second, shared, rays);
  }
}

template <class U>
using BvhTraversalTest = testing::UnitTest<U>;
TYPED_TEST_SUITE(BvhTraversalTest, testing::KernelUnits);

TYPED_TEST(BvhTraversalTest, SpheresMatchTheScanBitForBit) {
  constexpr KernelUnit kUnit = TestFixture::kUnit;
  RaySampler s(21);
  const RaySoA rays = traversal_rays(s);
  check_kind<kUnit>(random_spheres(s, 400), build_spheres,
                    study_sphere_streams<KernelUnit::scalar>(SphereMethod::robust),
                    study_sphere_bvh_streams<kUnit>(SphereMethod::robust), rays);
}

TYPED_TEST(BvhTraversalTest, TrianglesMatchTheScanBitForBit) {
  constexpr KernelUnit kUnit = TestFixture::kUnit;
  RaySampler s(22);
  const RaySoA rays = traversal_rays(s);
  check_kind<kUnit>(random_triangles(s, 400), build_triangles,
                    study_triangle_streams<KernelUnit::scalar>(TriangleMethod::watertight),
                    study_triangle_bvh_streams<kUnit>(TriangleMethod::watertight), rays);
  constexpr int kProductWidth[] = {kProductNodeWidth};
  check_kind<kUnit>(random_triangles(s, 400), build_triangles,
                    study_triangle_streams<KernelUnit::scalar>(TriangleMethod::moller_trumbore),
                    study_triangle_bvh_streams<kUnit>(TriangleMethod::moller_trumbore), rays, kProductWidth);
}

// A bumpy sheet of small triangles far from the world origin (cells of
// 0.02 at about 8,000), and rays leaving it as secondary rays do: from
// points just above random triangles, in random directions, so most hit a
// neighbour at a small t. Box planes then lie near ray origins of large
// |o|, where a slab test that rounds o * (1/d) without a margin culls
// children it must enter (NodeRay in geometry/bvh/node_ray.h).
std::vector<TriangleDesc> far_sheet(RaySampler& s, const Vec3<float>& corner, int side, float cell) {
  std::vector<float> height(static_cast<std::size_t>((side + 1) * (side + 1)));
  for (float& h : height) h = s.uniform(0.f, 0.6f * cell);
  const auto at = [&](int i, int j) {
    const float h = height[static_cast<std::size_t>(j * (side + 1) + i)];
    return corner + Vec3<float>(static_cast<float>(i) * cell, h, static_cast<float>(j) * cell);
  };
  std::vector<TriangleDesc> out;
  for (int j = 0; j < side; ++j) {
    for (int i = 0; i < side; ++i) {
      TriangleDesc lower, upper;
      lower.p = {at(i, j), at(i + 1, j), at(i + 1, j + 1)};
      upper.p = {at(i, j), at(i + 1, j + 1), at(i, j + 1)};
      out.push_back(lower);
      out.push_back(upper);
    }
  }
  return out;
}

RaySoA rays_leaving(RaySampler& s, const std::vector<TriangleDesc>& sheet, int count) {
  std::vector<Ray<float>> rays;
  for (int k = 0; k < count; ++k) {
    const TriangleDesc& t = sheet[static_cast<std::size_t>(s.uniform(0.f, 0.999f) * static_cast<float>(sheet.size()))];
    const float u = s.uniform(0.05f, 0.45f), v = s.uniform(0.05f, 0.45f);
    const Vec3<float> on = t.p[0] + (t.p[1] - t.p[0]) * u + (t.p[2] - t.p[0]) * v;
    rays.push_back({on + Vec3<float>(0.f, 0.002f, 0.f), s.unit_direction(), 0.f,
                    std::numeric_limits<float>::infinity()});
  }
  return padded_soa(rays);
}

TYPED_TEST(BvhTraversalTest, TrianglesFarFromTheOriginMatchTheScanBitForBit) {
  constexpr KernelUnit kUnit = TestFixture::kUnit;
  RaySampler s(25);
  const std::vector<TriangleDesc> sheet = far_sheet(s, {7000.f, -6000.f, 8000.f}, 24, 0.02f);
  check_kind<kUnit>(sheet, build_triangles, study_triangle_streams<KernelUnit::scalar>(TriangleMethod::watertight),
                    study_triangle_bvh_streams<kUnit>(TriangleMethod::watertight), rays_leaving(s, sheet, 3000));
}

// A flat square of triangles in the plane y = 0 and packets of rays from
// just above it in random directions (every octant in one packet): the up
// ones leave into open space, entering no child of the root (the streams
// answer them before any walk of their own), the down ones hit the square
// or pass its edge. Lanes of both kinds share packets.
TYPED_TEST(BvhTraversalTest, RaysLeavingAFlatFaceIntoOpenSpaceMatchTheScanBitForBit) {
  constexpr KernelUnit kUnit = TestFixture::kUnit;
  RaySampler s(27);
  std::vector<TriangleDesc> square;
  const float cell = 0.25f;
  for (int j = 0; j < 16; ++j) {
    for (int i = 0; i < 16; ++i) {
      const Vec3<float> c{static_cast<float>(i) * cell, 0.f, static_cast<float>(j) * cell};
      TriangleDesc lower, upper;
      lower.p = {c, c + Vec3<float>(cell, 0.f, 0.f), c + Vec3<float>(cell, 0.f, cell)};
      upper.p = {c, c + Vec3<float>(cell, 0.f, cell), c + Vec3<float>(0.f, 0.f, cell)};
      square.push_back(lower);
      square.push_back(upper);
    }
  }
  std::vector<Ray<float>> rays;
  for (int k = 0; k < 2000; ++k) {
    const Vec3<float> from{s.uniform(0.f, 4.f), 0.001f, s.uniform(0.f, 4.f)};
    Vec3<float> d = s.unit_direction();
    if (k % 3 != 0) d.y = std::fabs(d.y);  // two in three leave, one in three may hit
    rays.push_back({from, d, 0.f, std::numeric_limits<float>::infinity()});
  }
  const RaySoA soa = padded_soa(rays);
  check_kind<kUnit>(square, build_triangles, study_triangle_streams<KernelUnit::scalar>(TriangleMethod::watertight),
                    study_triangle_bvh_streams<kUnit>(TriangleMethod::watertight), soa);
}

// Rays from inside the scene whose interval reaches behind their origin
// (tmin -inf or -40, tmax +inf, 0 or -1): their closest hits lie at
// negative t, where the relative slab widening narrows the intervals and
// distances compared by their bits order backwards (the streams hand such
// rays to the single-ray walk, which enters every child).
RaySoA rays_reaching_behind(RaySampler& s, int count) {
  const float inf = std::numeric_limits<float>::infinity();
  const float tmins[2] = {-inf, -40.f}, tmaxs[3] = {inf, 0.f, -1.f};
  std::vector<Ray<float>> rays;
  for (int k = 0; k < count; ++k) {
    rays.push_back({s.in_box({-9, -9, -9}, {9, 9, 9}), s.unit_direction(), tmins[k % 2], tmaxs[k % 3]});
  }
  return padded_soa(rays);
}

// Near ties across nodes: along each ray a small sphere's pole lies at t
// and a big sphere, off to the side (its box entered long before its hit),
// is hit within a few ulps of t. The walk finds the big sphere first; the
// small one's node is entered about where the kernel puts its hit, which
// may round before the big one's or after its own box entry. The walk's
// slack on the current hit keeps visiting such nodes, so the closest hit
// (and the tie rule) is the scan's.
TYPED_TEST(BvhTraversalTest, NearTiesAcrossNodesMatchTheScanBitForBit) {
  constexpr KernelUnit kUnit = TestFixture::kUnit;
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<SphereDesc> spheres;
  std::vector<Ray<float>> rays;
  const double big = 5.0, aside = 4.9, depth = std::sqrt(big * big - aside * aside);
  for (int k = 0; k < 256; ++k) {
    const Vec3<double> o{30.0 * (k % 16), 30.0 * (k / 16), 0.0};
    const double t_small = 10.0 + unit(rng), r_small = 0.5 + unit(rng);
    const double t_big = t_small * (1.0 + (8.0 * unit(rng) - 4.0) * 0x1p-24);
    const SphereDesc small{{float(o.x), float(o.y), float(-(t_small + r_small))}, float(r_small)};
    const SphereDesc wide{{float(o.x), float(o.y + aside), float(-(t_big + depth))}, float(big)};
    spheres.push_back(k % 2 == 0 ? small : wide);
    spheres.push_back(k % 2 == 0 ? wide : small);
    rays.push_back({{float(o.x), float(o.y), 0.f}, {0.f, 0.f, -1.f}, 0.f, std::numeric_limits<float>::infinity()});
  }
  const RaySoA soa = padded_soa(rays);
  for (SphereMethod method : {SphereMethod::robust, SphereMethod::algebraic}) {
    SCOPED_TRACE(::testing::Message() << "method " << static_cast<int>(method));
    check_kind<kUnit>(spheres, build_spheres, study_sphere_streams<KernelUnit::scalar>(method),
                      study_sphere_bvh_streams<kUnit>(method), soa);
  }
}

TYPED_TEST(BvhTraversalTest, RaysReachingBehindTheirOriginMatchTheScanBitForBit) {
  constexpr KernelUnit kUnit = TestFixture::kUnit;
  RaySampler s(26);
  const RaySoA rays = rays_reaching_behind(s, 1500);
  check_kind<kUnit>(random_triangles(s, 400), build_triangles,
                    study_triangle_streams<KernelUnit::scalar>(TriangleMethod::watertight),
                    study_triangle_bvh_streams<kUnit>(TriangleMethod::watertight), rays);
  check_kind<kUnit>(random_spheres(s, 400), build_spheres,
                    study_sphere_streams<KernelUnit::scalar>(SphereMethod::robust),
                    study_sphere_bvh_streams<kUnit>(SphereMethod::robust), rays);
}

TYPED_TEST(BvhTraversalTest, PolygonsMatchTheScanBitForBit) {
  constexpr KernelUnit kUnit = TestFixture::kUnit;
  RaySampler s(23);
  const RaySoA rays = traversal_rays(s);
  check_kind<kUnit>(random_polygons(s, 300), build_polygons,
                    study_polygon_streams<KernelUnit::scalar>(PolygonMethod::crossing),
                    study_polygon_bvh_streams<kUnit>(PolygonMethod::crossing), rays);
}

TYPED_TEST(BvhTraversalTest, ConesMatchTheScanBitForBit) {
  constexpr KernelUnit kUnit = TestFixture::kUnit;
  RaySampler s(24);
  const RaySoA rays = traversal_rays(s);
  check_kind<kUnit>(random_cones(s, 300), build_cones, study_cone_streams<KernelUnit::scalar>(ConeMethod::quadric),
                    study_cone_bvh_streams<kUnit>(ConeMethod::quadric), rays);
}

}  // namespace
}  // namespace quiver
