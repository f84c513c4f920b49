// BVH traversal through one primitive store, or through the tested stores of
// a tree over two (a scene's opaque and transmissive layers, BvhStores),
// written once for every width:
//   packet: W rays walk the tree together (Wald, Slusallek, Benthin, Wagner,
//           "Interactive rendering with coherent ray tracing", 2001); a child
//           is entered when any active lane's slab interval meets it; a
//           popped entry keeps only the lanes whose entry distance is still
//           within their closest hit; leaves test W rays against one
//           primitive at a time (the packet kernels); when the active lanes
//           share an octant, an interval frustum around them first tests
//           all of a node's children at once, and only the children it
//           enters are tested lane by lane (NodeFrustum; any-hit packets:
//           through a tree over one store);
//   single: one ray tests all children of a wide node at once (a node's
//           boxes are SoA), nearest child first; leaves test the ray against
//           W primitives at a time (the scan kernels), or one at a time for
//           kinds without a scan orientation. A packet's rays that walk
//           one by one through watertight triangles are set up together
//           (node terms and frames in SIMD, then walked frame by frame).
// The stream decides per packet: packets travel together, except that
// triangle packets whose active lanes' directions span several octants
// (incoherent) traverse lane by lane (measured, bench/README.md).
//
// Slab test: Williams, Barrus, Morley, Shirley, "An efficient and robust
// ray-box intersection algorithm" (2005): near/far planes chosen by the sign
// of 1/d; each plane's distance one fma, p * (1/d) - o * (1/d), the offset
// moved by a margin that keeps the interval around the exact one (SlabTerms;
// a zero d as +-2^-80); a NaN distance is dropped by the order of the
// min/max operands. The interval is widened by kSlabSlack relative (beyond
// Ize's 2 gamma(3), "Robust BVH ray traversal", JCGT 2013, to cover the
// kernels' own error in t), so no primitive a brute-force scan reports is
// culled. The single-ray walks compare the distances by their bits, as
// integers (Embree's form, with shorter latencies), for rays
// with tmin >= 0 and finite slab terms (widened_interval_bits). The
// widening is relative, so it would narrow negative distances: a ray whose
// interval reaches behind its origin (tmin < 0) walks alone and enters
// every child.
//
// Closest hit: the lexicographic minimum of (t, id) over the store, as the
// brute-force scan in id order gives it: kernels get tmax = next_float_up(t)
// and a hit at exactly t wins only with a smaller id. So the result does not
// depend on traversal order, packet or single, or width.
// Any hit: occlusion within (tmin, tmax); a packet stops when every lane is
// blocked, a single ray at its first hit.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "geometry/bvh.h"
#include "geometry/streams.h"

namespace quiver {

// Relative widening of every slab interval: 2^-10, above the relative t
// error of every kernel in the stability tests.
inline constexpr float kSlabSlack = 0x1p-10f;

enum class BvhTraversal { automatic, packets, single };

// Lanes for one ray against a node's children, per kernel unit and node width.
template <KernelUnit U, int N>
struct NodeLanesOf {
  using type = float;  // children one at a time
};
#if XSIMD_WITH_SSE4_2 && defined(__FMA__)
template <>
struct NodeLanesOf<KernelUnit::sse4, 4> {
  using type = UnitLanes<KernelUnit::sse4>;
};
template <>
struct NodeLanesOf<KernelUnit::sse4, 8> {
  using type = UnitLanes<KernelUnit::sse4>;  // two halves
};
#endif
#if XSIMD_WITH_FMA3_AVX2
template <>
struct NodeLanesOf<KernelUnit::avx2, 4> {
  using type = xsimd::batch<float, xsimd::sse4_2>;
};
template <>
struct NodeLanesOf<KernelUnit::avx2, 8> {
  using type = UnitLanes<KernelUnit::avx2>;
};
#endif
#if XSIMD_WITH_AVX512BW
template <int N>
struct NodeLanesOf<KernelUnit::avx512, N> : NodeLanesOf<KernelUnit::avx2, N> {};  // nodes as in the avx2 unit
#endif

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

// Float offsets in a node block of width N of axis a's near and far
// planes: lo and hi, swapped when 1/d < 0 (reversed).
template <int N>
constexpr int near_plane_offset(int a, bool reversed) {
  return (reversed ? 3 + a : a) * N;
}
template <int N>
constexpr int far_plane_offset(int a, bool reversed) {
  return (reversed ? a : 3 + a) * N;
}

// The ratio by which the node tests widen an interval: entry <= exit *
// kSlabWidening whenever entry * (1 - kSlabSlack) <= exit * (1 +
// kSlabSlack) in rounded arithmetic (exit >= 0), with 8 ulps to spare for
// the roundings of exits scaled by it in advance.
inline constexpr float kSlabWidening = (1.f + kSlabSlack) / (1.f - kSlabSlack) * (1.f + 0x1p-21f);

// A ray's terms on one axis for the node tests. The entry distance of a
// plane p is one fma, p * (1/d) - offset (Embree's form: the path from one
// node to the next runs through it), offset = o * (1/d) moved by 2^-22
// |o * (1/d)| toward the conservative side (up for entries, down for
// exits), which covers the rounding of o * (1/d) and of the offset (each
// <= 2^-24 of it), so the interval contains the exact (p - o) * (1/d)'s;
// the fma's own rounding is relative and within the slack. Exits come
// scaled by kSlabWidening (1/d and the offset scaled per ray), so the test
// needs no multiply. A zero d is taken as +-2^-80 (sign kept): 1/d stays
// finite, and an axis-parallel ray tests the slab it lies in, widened by
// 2^-22 |o|.
template <class F>
struct SlabTerms {
  F entry_inv_dir, entry_offset, exit_inv_dir, exit_offset;  // offsets negated

  [[gnu::always_inline]] static SlabTerms of(const F& origin, const F& direction) {
    const F tiny(0x1p-80f);
    const F inv = F(1.f) / select(abs(direction) < tiny, copysign(tiny, direction), direction);
    const F offset = origin * inv;
    const F margin = F(0x1p-22f) * abs(offset);
    return {inv, -(offset + margin), inv * F(kSlabWidening), -((offset - margin) * F(kSlabWidening))};
  }
  // One ray's terms in every lane of G.
  template <class G>
  SlabTerms<G> broadcast() const {
    return {G(entry_inv_dir), G(entry_offset), G(exit_inv_dir), G(exit_offset)};
  }
  F entry(const F& plane) const { return fma(plane, entry_inv_dir, entry_offset); }
  F widened_exit(const F& plane) const { return fma(plane, exit_inv_dir, exit_offset); }
};

// The interval of a node test from its three entry and (widened) exit
// distances: max and min as two-level trees (a NaN distance drops out, and
// may take the other plane of its pair with it: never a child less), tmax
// widened as the exits are. `near` receives the entry times 1 - kSlabSlack
// (the walks' stack keys); the result: the interval is not empty.
template <class F>
[[gnu::always_inline]] inline Mask<F> widened_interval(const std::array<F, 3>& entry, const std::array<F, 3>& exit,
                                                       const F& tmin, const F& tmax, F& near) {
  const F t0 = max(max(tmin, entry[0]), max(entry[1], entry[2]));
  const F t1 = min(min(tmax * F(kSlabWidening), exit[0]), min(exit[1], exit[2]));
  near = t0 * F(1.f - kSlabSlack);
  return t0 <= t1;
}

// widened_interval on the distances' bits (float_bits), for rays whose
// node tests may compare them so (NodeRay::bits_ordered: tmin is +0 to +inf,
// and no distance can be NaN). The max is then the float max (negative
// entries lie below tmin), and a negative exit empties the interval as it
// does in floats, but for an exit of -0 at t0 = 0 (a box left exactly at
// the ray's origin, where no kernel reports t > tmin >= 0): the same lanes,
// the same keys. Integer max, min and compare shorten the path from one
// node to the next. Returns the entered lanes' bits.
template <class F>
[[gnu::always_inline]] inline unsigned widened_interval_bits(const std::array<F, 3>& entry,
                                                             const std::array<F, 3>& exit, const F& tmin,
                                                             const F& tmax, F& near) {
  const auto t0 = bits_max(bits_max(float_bits(tmin), float_bits(entry[0])),
                           bits_max(float_bits(entry[1]), float_bits(entry[2])));
  const auto t1 = bits_min(bits_min(float_bits(tmax * F(kSlabWidening)), float_bits(exit[0])),
                           bits_min(float_bits(exit[1]), float_bits(exit[2])));
  near = float_of_bits(t0) * F(1.f - kSlabSlack);
  return bits_at_most(t0, t1);
}

// A packet set up for slab tests against a node's children. When every
// active lane's 1/d has the same signs, each axis' near and far planes are
// the same for all lanes and are chosen once (no per-lane select); other
// lanes are masked off by the caller.
template <class F, int N>
struct PacketSlab {
  Vec3<F> origin;
  std::array<SlabTerms<F>, 3> terms;
  std::array<Mask<F>, 3> negative;               // 1/d < 0: the near plane is hi
  bool same_planes = true;
  std::array<bool, 3> reversed{};                // some active lane's 1/d < 0
  std::array<int, 3> near_plane{}, far_plane{};  // float offsets in a node block

  PacketSlab(const Ray<F>& r, const Mask<F>& active)
      : origin(r.origin),
        terms{SlabTerms<F>::of(r.origin.x, r.direction.x), SlabTerms<F>::of(r.origin.y, r.direction.y),
              SlabTerms<F>::of(r.origin.z, r.direction.z)} {
    for (int a = 0; a < 3; ++a) {
      negative[a] = terms[a].entry_inv_dir < F(0.f);
      reversed[a] = any(negative[a] && active);
      same_planes = same_planes && !(reversed[a] && any(and_not(active, negative[a])));
      near_plane[a] = near_plane_offset<N>(a, reversed[a]);
      far_plane[a] = far_plane_offset<N>(a, reversed[a]);
    }
  }

  // Lanes entering child c of a node block within [tmin, tmax] (widened as
  // enter_children does); near receives their entry distances times 1 - kSlabSlack.
  Mask<F> enters(const float* block, int c, const F& tmin, const F& tmax, F& near) const {
    std::array<F, 3> entry, exit;
    const float* box = block + c;
    for (int a = 0; a < 3; ++a) {
      const F near_plane_lanes = same_planes ? F(box[near_plane[a]])
                                             : select(negative[a], F(box[far_plane_offset<N>(a, false)]),
                                                      F(box[near_plane_offset<N>(a, false)]));
      const F far_plane_lanes = same_planes ? F(box[far_plane[a]])
                                            : select(negative[a], F(box[near_plane_offset<N>(a, false)]),
                                                     F(box[far_plane_offset<N>(a, false)]));
      entry[a] = terms[a].entry(near_plane_lanes);
      exit[a] = terms[a].widened_exit(far_plane_lanes);
    }
    return widened_interval(entry, exit, tmin, tmax, near);
  }
};

// The closest-hit rule: a candidate at exactly the current t wins only with a smaller id.
template <class F>
inline Mask<F> wins_over(const Mask<F>& hit, const F& t, const IntLanes<F>& id, const Hit<F>& best) {
  return hit && (t < best.t || (t == best.t && int_less(id, best.id)));
}

// Primitive stores with a scan orientation (one ray, W primitives).
template <class S>
concept ScanStore = requires(const S& s) { s.template load<float>(0); };

// The stores a query walks through a BVH and tests. K = 1: the tree's one
// store, every leaf tested (its store bit is not read). K = 2: the tree
// indexes two stores (leaf_store picks one, both non-null) and the query
// tests those in `tested` (bit s for store s): the packet walks and the
// any-hit walk never push a leaf of the others, the closest-hit single-ray
// walk may reach one and tests nothing in it. One store is a compile-time
// case: choosing the store per leaf measured 3-9% slower on balls-s4's
// packets.
template <class S, int K>
struct BvhStores;

template <class S>
struct BvhStores<S, 1> {
  const S* store;

  static constexpr bool tests(std::int32_t) { return true; }
  const S& of(std::int32_t) const { return *store; }
};

template <class S>
struct BvhStores<S, 2> {
  std::array<const S*, 2> store;
  unsigned tested;

  bool tests(std::int32_t leaf) const { return ((tested >> leaf_store(leaf)) & 1u) != 0; }
  const S& of(std::int32_t leaf) const { return *store[static_cast<std::size_t>(leaf_store(leaf))]; }
};

// A child slot a walk enters: an inner node, or a non-empty leaf of a tested store.
template <class S, int K>
inline bool worth_entering(const BvhStores<S, K>& stores, std::int32_t child) {
  return !is_leaf(child) || (leaf_count(child) != 0 && stores.tests(child));
}

// ---- a node's children in one pass ----------------------------------------------

// Whether a ray's node tests may compare distances by their bits
// (widened_interval_bits): tmin is +0 to +inf (sign bit clear, not NaN),
// and on each axis 1/d is finite and not zero and the offsets are finite,
// so a plane's distance (box planes are numbers or +-inf) is never NaN.
// (|1/d| <= 2^80, so exit_inv_dir is finite with entry_inv_dir.)
template <class F>
inline Mask<F> orders_by_bits(const F& tmin, const SlabTerms<F>& axis_terms, const Mask<F>& other_axes) {
  return other_axes && axis_terms.entry_inv_dir != F(0.f) && isfinite_lanes(axis_terms.entry_inv_dir) &&
         isfinite_lanes(axis_terms.entry_offset) && isfinite_lanes(axis_terms.exit_offset) &&
         copysign(F(1.f), tmin) > F(0.f) && tmin == tmin;
}

// The node-test terms of a packet's rays for walks ray by ray, set up for
// all lanes at once (SlabTerms on the packet's lanes: per lane the
// operations NodeRay does for one ray, so the same bits) and stored per
// lane, so that each ray starts from loads instead of its own divisions.
// Only lanes NodeRay would mark bits_ordered are set up (`ordered`).
template <class F>
struct LaneNodeTerms {
  static constexpr std::size_t kLanes = lane_count<F>;
  // Axis a's entry_inv_dir, entry_offset, exit_inv_dir, exit_offset at 4a .. 4a + 3.
  alignas(64) std::array<std::array<float, kLanes>, 12> terms;
  alignas(64) std::array<float, kLanes> tmin;
  std::array<unsigned, 3> reversed{};  // lanes whose 1/d < 0, per axis
  unsigned ordered = 0;

  explicit LaneNodeTerms(const Ray<F>& ray) {
    Mask<F> ordered_lanes(true);
    for (std::size_t a = 0; a < 3; ++a) {
      const SlabTerms<F> t = SlabTerms<F>::of(ray.origin[static_cast<int>(a)], ray.direction[static_cast<int>(a)]);
      store_lanes(t.entry_inv_dir, terms[4 * a].data());
      store_lanes(t.entry_offset, terms[4 * a + 1].data());
      store_lanes(t.exit_inv_dir, terms[4 * a + 2].data());
      store_lanes(t.exit_offset, terms[4 * a + 3].data());
      reversed[a] = lane_bits(t.entry_inv_dir < F(0.f));
      ordered_lanes = orders_by_bits(ray.tmin, t, ordered_lanes);
    }
    store_lanes(ray.tmin, tmin.data());
    ordered = lane_bits(ordered_lanes);
  }
};

// One ray set up for a node's children: its SlabTerms in node lanes, and
// per axis the near and far plane (lo or hi by the sign of 1/d), chosen
// once per ray.
template <KernelUnit U, int N>
struct NodeRay {
  using G = typename NodeLanesOf<U, N>::type;
  std::array<SlabTerms<G>, 3> terms;
  std::array<int, 3> near_plane, far_plane;  // float offsets in the block
  // The node tests may compare distances by their bits (orders_by_bits).
  bool bits_ordered;
  // The node tests' lower bound: the ray's tmin, or -inf when tmin < 0. The
  // slab widening, relative, would narrow negative distances, so a ray
  // reaching behind its origin enters every child (a scan through the tree):
  // its terms give every plane the distance -inf (entries) or +inf (exits),
  // or NaN for a plane at +-inf, which the float test drops.
  float tmin;

  explicit NodeRay(const Ray<float>& ray)
      : bits_ordered(true),
        tmin(ray.tmin < 0.f ? -std::numeric_limits<float>::infinity() : ray.tmin) {
    constexpr float inf = std::numeric_limits<float>::infinity();
    for (int a = 0; a < 3; ++a) {
      const SlabTerms<float> one = SlabTerms<float>::of(ray.origin[a], ray.direction[a]);
      const bool reversed = one.entry_inv_dir < 0.f;
      terms[a] = ray.tmin < 0.f ? SlabTerms<float>{0.f, -inf, 0.f, inf}.template broadcast<G>()
                                : one.template broadcast<G>();
      near_plane[a] = near_plane_offset<N>(a, reversed);
      far_plane[a] = far_plane_offset<N>(a, reversed);
      bits_ordered = orders_by_bits(ray.tmin, one, bits_ordered);
    }
  }
  // One lane of a packet's terms, a lane they mark ordered: the same values
  // as NodeRay(that lane's ray).
  template <class F>
  NodeRay(const LaneNodeTerms<F>& lanes, int lane) : bits_ordered(true) {
    const std::size_t k = static_cast<std::size_t>(lane);
    tmin = lanes.tmin[k];
    for (std::size_t a = 0; a < 3; ++a) {
      terms[a] = SlabTerms<float>{lanes.terms[4 * a][k], lanes.terms[4 * a + 1][k], lanes.terms[4 * a + 2][k],
                                  lanes.terms[4 * a + 3][k]}
                     .template broadcast<G>();
      const bool reversed = ((lanes.reversed[a] >> lane) & 1u) != 0;
      near_plane[a] = near_plane_offset<N>(static_cast<int>(a), reversed);
      far_plane[a] = far_plane_offset<N>(static_cast<int>(a), reversed);
    }
  }
  G entry(int a, const G& plane) const { return terms[a].entry(plane); }
  G widened_exit(int a, const G& plane) const { return terms[a].widened_exit(plane); }
};

// Some active lane's interval reaches behind its origin (tmin < 0): such
// packets go to the single-ray walks (travels_together, NodeRay::tmin).
template <class F>
inline bool reaches_behind(const Ray<F>& ray, const Mask<F>& active) {
  return any(ray.tmin < F(0.f) && active);
}

// A packet's active rays bounded per axis, origins and 1/d as intervals, so
// that one pass over a node's children finds those some lane may enter
// before they are tested lane by lane (the interval frustum of Reshetov,
// Soupikov, Hurley, "Multi-level ray tracing algorithm", 2005; Embree's
// coherent packets). Usable when the active lanes share an octant and every
// tmin >= 0: then an axis' entry distance is smallest for the origin
// farthest along the direction and the 1/d nearest zero, its exit distance
// largest for the other two bounds (an entry below zero is cut by tmin);
// rounding is monotone, so a child's interval contains every lane's. A NaN
// in an active lane (its origin, 1/d, tmin or tmax) makes it unusable: the
// reductions would drop it, and with it another lane's bound.
template <KernelUnit U, int N>
struct NodeFrustum {
  using G = typename NodeLanesOf<U, N>::type;
  // The exits' 1/d bounds come scaled by kSlabWidening.
  std::array<G, 3> origin_at_entry, inv_dir_at_entry, origin_at_exit, inv_dir_at_exit;
  std::array<int, 3> near_plane, far_plane;
  float tmin = 0.f, tmax = 0.f;  // the smallest tmin and the largest tmax of the active lanes
  bool usable = false;

  NodeFrustum() = default;  // unusable
  template <class F>
  NodeFrustum(const PacketSlab<F, N>& slab, const F& tmin_lanes, const F& tmax_lanes, const Mask<F>& active)
      : near_plane(slab.near_plane), far_plane(slab.far_plane) {
    Mask<F> numbers = tmin_lanes >= F(0.f) && tmax_lanes == tmax_lanes;
    for (int a = 0; a < 3; ++a) {
      numbers = numbers && slab.origin[a] == slab.origin[a] &&
                slab.terms[a].entry_inv_dir == slab.terms[a].entry_inv_dir;
    }
    if (!slab.same_planes || !all(numbers || !active)) return;
    const F inf(std::numeric_limits<float>::infinity());
    const auto smallest = [&](const F& v) { return horizontal_min(select(active, v, inf)); };
    const auto largest = [&](const F& v) { return horizontal_max(select(active, v, -inf)); };
    for (int a = 0; a < 3; ++a) {
      const F& o = slab.origin[a];
      const F& inv = slab.terms[a].entry_inv_dir;
      const bool rev = slab.reversed[a];
      origin_at_entry[a] = G(rev ? smallest(o) : largest(o));
      inv_dir_at_entry[a] = G(rev ? largest(inv) : smallest(inv));
      origin_at_exit[a] = G(rev ? largest(o) : smallest(o));
      inv_dir_at_exit[a] = G((rev ? smallest(inv) : largest(inv)) * kSlabWidening);
    }
    tmin = smallest(tmin_lanes);
    tmax = largest(tmax_lanes);
    usable = true;
  }
  G entry(int a, const G& plane) const { return (plane - origin_at_entry[a]) * inv_dir_at_entry[a]; }
  G widened_exit(int a, const G& plane) const { return (plane - origin_at_exit[a]) * inv_dir_at_exit[a]; }
};

// The node's children a NodeRay or a NodeFrustum enters within [its tmin,
// tmax] (widened_interval): bit c of the result, near[c] their keys.
template <int N, bool kBits = false, class R>
[[gnu::always_inline]] inline unsigned enter_children(const float* block, const R& ray, float tmax,
                                                      std::array<float, N>& near) {
  using G = typename R::G;
  constexpr int kG = lane_count<G>;
  unsigned bits = 0;
  for (int c = 0; c < N; c += kG) {
    std::array<G, 3> entry, exit;
    for (int a = 0; a < 3; ++a) {
      entry[a] = ray.entry(a, load_lanes<G>(block + ray.near_plane[a] + c));
      exit[a] = ray.widened_exit(a, load_lanes<G>(block + ray.far_plane[a] + c));
    }
    G lane_near;
    if constexpr (kBits) {
      bits |= widened_interval_bits(entry, exit, G(ray.tmin), G(tmax), lane_near) << c;
    } else {
      bits |= lane_bits(widened_interval(entry, exit, G(ray.tmin), G(tmax), lane_near)) << c;
    }
    if constexpr (kG == 1) {
      near[c] = lane_near;
    } else {
      store_lanes(lane_near, near.data() + c);
    }
  }
  return bits;
}

// ---- packet traversal -------------------------------------------------------

// Calls visit(c) for the children c of an N-wide node a packet tests, in
// order (kLastFirst: N-1 down to 0): without a frustum every child, in a
// counted loop; after one (kSome) the children in `candidates`, bit by bit.
// (One loop form for both measured slower: bit by bit over all children,
// gears-s4's diffuse packets -7%; a counted loop skipping non-candidates,
// the bunny's primary packets -7%.)
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
      const S& prims = stores.of(entry_node);
      const std::int32_t first = leaf_first(entry_node), end = first + leaf_count(entry_node);
      for (std::int32_t p = first; p < end; ++p) {
        Candidate<F> c;
        const Mask<F> hits_p = Method::intersect(prepared, prims.template broadcast<F>(static_cast<std::size_t>(p)),
                                                 next_float_up(hit.t), lanes, c);
        const IntLanes<F> id(prims.id_base + p);
        const Mask<F> closer = wins_over(hits_p, c.t, id, hit);
        if (any(closer)) {
          hit.commit(closer, c, id);
          if constexpr (kCulls) frustum_tmax = horizontal_max(select(active, hit.t, -inf));
        }
      }
      continue;
    }
    // Children that some lane enters, pushed farthest first (insertion into the stack top).
    std::array<float, bvh_stack_size(N)> key;
    const std::size_t base = top;
    const float* block = nodes.block(entry_node);
    const auto push = [&](std::int32_t child, const F& lane_near) __attribute__((always_inline)) {
      const float k = horizontal_min(lane_near);
      std::size_t at = top++;
      for (; at > base && key[at - 1] < k; --at) {
        key[at] = key[at - 1];
        stack_node[at] = stack_node[at - 1];
        stack_near[at] = stack_near[at - 1];
      }
      key[at] = k;
      stack_node[at] = child;
      stack_near[at] = lane_near;
    };
    if constexpr (kCulls) {
      std::array<float, N> unused;
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
        // One store: no check, an empty slot's empty box lets no lane in (measured faster on balls-s4).
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
      const S& prims = stores.of(entry_node);
      const std::int32_t first = leaf_first(entry_node), end = first + leaf_count(entry_node);
      for (std::int32_t p = first; p < end; ++p) {
        const Mask<F> open = and_not(entry_lanes, occluded);
        if (none(open)) break;
        Candidate<F> unused;
        occluded = occluded || Method::intersect(prepared, prims.template broadcast<F>(static_cast<std::size_t>(p)),
                                                 ray.tmax, open, unused);
      }
      continue;
    }
    const float* block = nodes.block(entry_node);
    unsigned candidates = 0;
    if constexpr (kCulls) {
      std::array<float, N> unused;
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

// ---- single-ray traversal -----------------------------------------------------

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

// Method::intersect for unit U. GCC leaves the one-ray (float) test of a
// kind without a scan orientation out of line in the single-ray walks; a
// plain call would then reach one copy, built with one unit's flags, from
// every unit. Flattened into a function whose name carries U, each unit keeps
// its own (tests/geometry_streams_unit_symbols_test.cmake). Forcing that
// test inline instead cost gears-s4's packets 2.5-5%.
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
// (six), chosen once per ray: the bunny's single rays measured 5-10% faster
// than choosing the frame at every leaf block (bench/README.md).
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
// behind its origin, NodeRay::tmin). Other kinds keep one copy, on the floats: the
// two copies made teapot-s12's polygon walk about a third slower (perf;
// its per-ray setup weighs much there).
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

// The closest-hit walk of one ray: descends into the nearest entered child
// directly and pushes the others, farthest first; a popped entry is culled
// against the current hit. The hit is a local copy (stores through a
// reference kept the tree's fields from staying in registers).
template <KernelUnit U, int N, bool kBits, class S, int K, class Leaf>
[[gnu::always_inline]] inline Hit<float> closest_single_walk(BvhStores<S, K> stores, BvhNodes<N> nodes,
                                                             const NodeRay<U, N>& node_ray, const Leaf& leaf_ray,
                                                             Hit<float> hit) {
  using F = LeafScanLanes<U>;
  struct Entry {
    std::int32_t node;
    float near;
  };
  std::array<Entry, bvh_stack_size(N)> stack;
  std::size_t top = 0;
  std::int32_t current = 0;
  for (;;) {
    if (is_leaf(current)) {
      const S& prims = stores.of(current);
      const std::size_t first = static_cast<std::size_t>(leaf_first(current));
      // A leaf of an untested store: an empty range.
      const std::size_t end = stores.tests(current) ? first + static_cast<std::size_t>(leaf_count(current)) : first;
      if constexpr (ScanStore<S>) {
        for (std::size_t block = first; block < end; block += lane_count<F>) {
          Candidate<F> c;
          const Mask<F> hits_block = leaf_ray.intersect(prims.template load<F>(block), F(next_float_up(hit.t)),
                                                        first_lanes<F>(end - block), c);
          if (none(hits_block)) continue;
          // Ids rise with the lane, so of the block's nearest hits the lowest lane has the smallest id.
          const int lane = __builtin_ctz(nearest_lanes(hits_block, c.t));
          const std::int32_t id = prims.id_base + static_cast<std::int32_t>(block) + lane;
          const float t = lane_value(c.t, lane);
          if (wins_over(true, t, id, hit)) {
            hit = {t, lane_value(c.u, lane), lane_value(c.v, lane),
                   {lane_value(c.ng.x, lane), lane_value(c.ng.y, lane), lane_value(c.ng.z, lane)}, id};
          }
        }
      } else {
        for (std::size_t p = first; p < end; ++p) {
          Candidate<float> c;
          const bool hits_p = leaf_ray.intersect(prims.template broadcast<float>(p), next_float_up(hit.t), true, c);
          const std::int32_t id = prims.id_base + static_cast<std::int32_t>(p);
          if (wins_over(hits_p, c.t, id, hit)) hit.commit(true, c, id);
        }
      }
    } else {
      std::array<float, N> near;
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
        // Several: push all, farthest first (insertion into the stack top), then take the nearest.
        const std::size_t base = top;
        for (;;) {
          std::size_t at = top++;
          for (; at > base && stack[at - 1].near < near[c]; --at) stack[at] = stack[at - 1];
          stack[at] = {BvhNodes<N>::child(block, c), near[c]};
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
      const Entry entry = stack[--top];
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
        for (std::size_t block = first; block < end; block += lane_count<F>) {
          Candidate<F> unused;
          if (any(leaf_ray.intersect(prims.template load<F>(block), F(tmax), first_lanes<F>(end - block), unused))) {
            return true;
          }
        }
      } else {
        for (std::size_t p = first; p < end; ++p) {
          Candidate<float> unused;
          if (leaf_ray.intersect(prims.template broadcast<float>(p), tmax, true, unused)) return true;
        }
      }
      continue;
    }
    std::array<float, N> near;
    const float* block = nodes.block(entry);
    for (unsigned bits = enter_children<N, kBits>(block, node_ray, tmax, near); bits != 0;
         bits &= bits - 1) {
      // Never an empty slot (empty boxes are never entered), yet dropping
      // that test measured 4-5% slower on the bunny's and balls-s4's shadow rays.
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

// ---- a packet's rays one by one ---------------------------------------------------

// Methods whose scans prepare a packet's rays at once and hand them over
// lane by lane in compile-time frames (the watertight triangle test).
template <class Method, class F>
concept PreparesLanesByFrame = requires(const Ray<F>& ray) { Method::prepare_lanes(ray); };

// Walks ray by ray with the packet's setup done at once: scan stores
// whose method prepares lanes by frame.
template <class Method, class S, class F>
concept WalksLanesByFrame = ScanStore<S> && PreparesLanesByFrame<Method, F>;

// A packet's closest hits stored per lane, for its rays' walks one by one.
template <class F>
struct LaneHits {
  static constexpr std::size_t kLanes = lane_count<F>;
  alignas(64) std::array<float, kLanes> t, u, v, ngx, ngy, ngz;
  alignas(64) std::array<std::int32_t, kLanes> id;

  explicit LaneHits(const Hit<F>& hit) {
    store_lanes(hit.t, t.data());
    store_lanes(hit.u, u.data());
    store_lanes(hit.v, v.data());
    store_lanes(hit.ng.x, ngx.data());
    store_lanes(hit.ng.y, ngy.data());
    store_lanes(hit.ng.z, ngz.data());
    store_int_lanes<F>(hit.id, id.data());
  }
  Hit<float> get(std::size_t k) const { return {t[k], u[k], v[k], {ngx[k], ngy[k], ngz[k]}, id[k]}; }
  void set(std::size_t k, const Hit<float>& hit) {
    t[k] = hit.t;
    u[k] = hit.u;
    v[k] = hit.v;
    ngx[k] = hit.ng.x;
    ngy[k] = hit.ng.y;
    ngz[k] = hit.ng.z;
    id[k] = hit.id;
  }
  Hit<F> packet() const {
    return {load_lanes<F>(t.data()), load_lanes<F>(u.data()), load_lanes<F>(v.data()),
            Vec3<F>(load_lanes<F>(ngx.data()), load_lanes<F>(ngy.data()), load_lanes<F>(ngz.data())),
            load_int_lanes<F>(id.data())};
  }
};

// One lane's closest-hit walk, for Method::for_each_lane_by_frame.
template <KernelUnit U, class Method, int N, class S, int K, class F>
struct LaneClosestWalk {
  BvhStores<S, K> stores;
  BvhNodes<N> nodes;
  const LaneNodeTerms<F>& node_terms;
  LaneHits<F>& hits;

  template <class Prepared, class Axes>
  [[gnu::always_inline]] void operator()(int lane, const Prepared& prepared, Axes) const {
    const std::size_t k = static_cast<std::size_t>(lane);
    const NodeRay<U, N> node_ray(node_terms, lane);
    const LeafRay<U, Method, Prepared, Axes> leaf_ray{prepared};
    hits.set(k, closest_single_walk<U, N, true>(stores, nodes, node_ray, leaf_ray, hits.get(k)));
  }
};

// One lane's any-hit walk, for Method::for_each_lane_by_frame.
template <KernelUnit U, class Method, int N, class S, int K, class F>
struct LaneOccludedWalk {
  BvhStores<S, K> stores;
  BvhNodes<N> nodes;
  const LaneNodeTerms<F>& node_terms;
  const std::array<float, lane_count<F>>& tmax;
  unsigned& blocked;

  template <class Prepared, class Axes>
  [[gnu::always_inline]] void operator()(int lane, const Prepared& prepared, Axes) const {
    const NodeRay<U, N> node_ray(node_terms, lane);
    if (occluded_single_walk<U, N, true>(stores, nodes, node_ray, LeafRay<U, Method, Prepared, Axes>{prepared},
                                         tmax[static_cast<std::size_t>(lane)])) {
      blocked |= 1u << lane;
    }
  }
};

// The closest hits of a packet's `lanes` (bits), ray by ray. The packet's
// node terms and frames are set up at once (LaneNodeTerms,
// Method::prepare_lanes) and its rays walked frame by frame, so no ray
// pays for its own divisions and frame branches (fandisk's diffuse rays,
// one or two node visits each, spent about half their time in that setup:
// bench/README.md); a lane those terms do not cover walks through
// closest_bvh_single. Out of line and flattened, as closest_bvh_single.
template <KernelUnit U, class Method, int N, class S, int K>
[[gnu::noinline, gnu::flatten]] void closest_bvh_lanes(BvhStores<S, K> stores, const Bvh& bvh, const RaySoA& rays,
                                                       std::size_t first, unsigned lanes, HitSoA& hits) {
  using F = UnitLanes<U>;
  const Ray<F> ray = rays.load<F>(first);
  const LaneNodeTerms<F> node_terms(ray);
  const unsigned set_up = lanes & node_terms.ordered;
  if (set_up != 0) {
    LaneHits<F> lane_hits(hits.load<F>(first));
    Method::template for_each_lane_by_frame<LeafScanLanes<U>>(
        Method::prepare_lanes(ray), set_up,
        LaneClosestWalk<U, Method, N, S, K, F>{stores, BvhNodes<N>(bvh), node_terms, lane_hits});
    hits.store(first, lane_hits.packet());
  }
  for (unsigned rest = lanes & ~set_up; rest != 0; rest &= rest - 1) {
    const std::size_t r = first + static_cast<std::size_t>(__builtin_ctz(rest));
    Hit<float> hit = hits.get(r);
    closest_bvh_single<U, Method, N>(stores, bvh, rays.get(r), hit);
    hits.set(r, hit);
  }
}

// Any hits of a packet's `lanes` (bits), ray by ray, as closest_bvh_lanes.
template <KernelUnit U, class Method, int N, class S, int K>
[[gnu::noinline, gnu::flatten]] void occluded_bvh_lanes(BvhStores<S, K> stores, const Bvh& bvh, const RaySoA& rays,
                                                        std::size_t first, unsigned lanes, OcclusionSoA& result) {
  using F = UnitLanes<U>;
  const Ray<F> ray = rays.load<F>(first);
  const LaneNodeTerms<F> node_terms(ray);
  const unsigned set_up = lanes & node_terms.ordered;
  unsigned blocked = 0;
  if (set_up != 0) {
    alignas(64) std::array<float, lane_count<F>> tmax;
    store_lanes(ray.tmax, tmax.data());
    Method::template for_each_lane_by_frame<LeafScanLanes<U>>(
        Method::prepare_lanes(ray), set_up,
        LaneOccludedWalk<U, Method, N, S, K, F>{stores, BvhNodes<N>(bvh), node_terms, tmax, blocked});
  }
  for (unsigned rest = lanes & ~set_up; rest != 0; rest &= rest - 1) {
    const int lane = __builtin_ctz(rest);
    if (occluded_bvh_single<U, Method, N>(stores, bvh, rays.get(first + static_cast<std::size_t>(lane)))) {
      blocked |= 1u << lane;
    }
  }
  for (; blocked != 0; blocked &= blocked - 1) {
    result.occluded[first + static_cast<std::size_t>(__builtin_ctz(blocked))] = 1;
  }
}

// ---- streams --------------------------------------------------------------------

// Every active lane's direction in one octant.
template <class F>
inline bool same_octant(const Ray<F>& ray, const Mask<F>& active) {
  for (int a = 0; a < 3; ++a) {
    const Mask<F> negative = ray.direction[a] < F(0.f);
    if (any(negative && active) && any(and_not(active, negative))) return false;
  }
  return true;
}

// Stores whose incoherent rays traverse faster one by one (scan leaves):
// triangles. Polygon packets were faster together on every ray set
// measured (bench/README.md). Spheres stay together too: the octant rule
// gained 15% on balls-s4's diffuse rays but lost 7% on its reflection rays,
// and reflections are what a Whitted renderer traces. Cones follow spheres.
template <class S>
concept IncoherentRaysTraverseAlone = S::kIncoherentRaysTraverseAlone;

// Whether the packet's active lanes walk the tree together: never when one
// reaches behind its origin (the packet walks' slab tests need tmin >= 0),
// else as the traversal says; automatic: triangles only within one octant.
// (Any-hit triangle packets one by one won 9% on the bunny's shadow rays
// and lost 38% on teapot-s12's, so they follow the same rule. Handing a packet's last 1, 2 or 3 lanes to the single-ray walk
// (Benthin et al. 2012) gained at most 3% (bunny primary rays) and lost up
// to 23% (gears-s4 shadow rays), so it is not used.)
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
    if constexpr (WalksLanesByFrame<Method, S, F>) {
      closest_bvh_lanes<U, Method, N>(stores, bvh, rays, first, lane_bits(active), hits);
      continue;
    }
    const std::size_t end = first + W < rays.count ? first + W : rays.count;
    for (std::size_t r = first; r < end; ++r) {
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
      // children without a box test, which leaves it little to save
      // (gears-s4: shadow rays -3..-5%, its whole render -5%).
      const PacketSlab<F, N> slab(ray, open);
      const NodeFrustum<U, N> frustum =
          K == 1 ? NodeFrustum<U, N>(slab, ray.tmin, ray.tmax, open) : NodeFrustum<U, N>();
      const Mask<F> blocked =
          frustum.usable ? occluded_bvh_packet<true, U, Method>(stores, bvh, ray, slab, frustum, occluded, valid)
                         : occluded_bvh_packet<false, U, Method>(stores, bvh, ray, slab, frustum, occluded, valid);
      store_int_lanes<F>(select(blocked, IntLanes<F>(1), IntLanes<F>(0)), result.occluded.data() + first);
      continue;
    }
    if constexpr (WalksLanesByFrame<Method, S, F>) {
      occluded_bvh_lanes<U, Method, N>(stores, bvh, rays, first, lane_bits(open), result);
      continue;
    }
    const std::size_t end = first + W < rays.count ? first + W : rays.count;
    for (std::size_t r = first; r < end; ++r) {
      if (result.occluded[r] == 0 && occluded_bvh_single<U, Method, N>(stores, bvh, rays.get(r))) {
        result.occluded[r] = 1;
      }
    }
  }
}

// The BVH streams of one method for node widths 2, 4 and 8, through a tree
// over one store or through the tested stores of a tree over two.
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
  void closest_hits(const RaySoA& rays, const S& prims, const Bvh& bvh, HitSoA& hits,
                    BvhTraversal traversal = BvhTraversal::automatic) const {
    closest[slot(bvh.width)](rays, BvhStores<S, 1>{&prims}, bvh, hits, traversal);
  }
  void any_hits(const RaySoA& rays, const S& prims, const Bvh& bvh, OcclusionSoA& result,
                BvhTraversal traversal = BvhTraversal::automatic) const {
    occluded[slot(bvh.width)](rays, BvhStores<S, 1>{&prims}, bvh, result, traversal);
  }
  void closest_hits(const RaySoA& rays, BvhStores<S, 2> stores, const Bvh& bvh, HitSoA& hits,
                    BvhTraversal traversal = BvhTraversal::automatic) const {
    closest_of_two[slot(bvh.width)](rays, stores, bvh, hits, traversal);
  }
  void any_hits(const RaySoA& rays, BvhStores<S, 2> stores, const Bvh& bvh, OcclusionSoA& result,
                BvhTraversal traversal = BvhTraversal::automatic) const {
    occluded_of_two[slot(bvh.width)](rays, stores, bvh, result, traversal);
  }
};

template <KernelUnit U, class Method, class S>
BvhStreams<S> make_bvh_streams() {
  BvhStreams<S> s;
  s.closest = {&closest_bvh<U, Method, S, 2, 1>, &closest_bvh<U, Method, S, 4, 1>, &closest_bvh<U, Method, S, 8, 1>};
  s.occluded = {&occluded_bvh<U, Method, S, 2, 1>, &occluded_bvh<U, Method, S, 4, 1>,
                &occluded_bvh<U, Method, S, 8, 1>};
  s.closest_of_two = {&closest_bvh<U, Method, S, 2, 2>, &closest_bvh<U, Method, S, 4, 2>,
                      &closest_bvh<U, Method, S, 8, 2>};
  s.occluded_of_two = {&occluded_bvh<U, Method, S, 2, 2>, &occluded_bvh<U, Method, S, 4, 2>,
                       &occluded_bvh<U, Method, S, 8, 2>};
  return s;
}

}  // namespace quiver
