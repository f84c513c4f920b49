// One ray, or a packet's bounds, set up for a node's children: the slab
// terms in node lanes (NodeLanesOf: the unit's own lanes, or SSE lanes for
// 4-wide nodes), the near and far planes chosen once, and the node test
// that finds the children it enters (enter_children). NodeRay: one ray;
// LaneNodeTerms: a packet's rays set up at once for walks one by one;
// NodeFrustum: interval bounds around a packet's rays.
#pragma once

#include <array>
#include <cstddef>
#include <limits>

#include "geometry/bvh/slab.h"
#include "simd/ray.h"

namespace quiver {

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

inline namespace QUIVER_UNIT_NAMESPACE {

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

// A node's children's entry keys, as enter_children writes them: a lane
// group at a time, with aligned stores, so the type carries the alignment.
template <int N>
struct alignas(64) ChildKeys : std::array<float, N> {};

// The node's children a NodeRay or a NodeFrustum enters within [its tmin,
// tmax] (widened_interval): bit c of the result, near[c] their keys.
template <int N, bool kBits = false, class R>
[[gnu::always_inline]] inline unsigned enter_children(const float* block, const R& ray, float tmax,
                                                      ChildKeys<N>& near) {
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

}  // namespace QUIVER_UNIT_NAMESPACE
}  // namespace quiver
