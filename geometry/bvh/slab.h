// Slab tests of a ray against a BVH node's child boxes: Williams, Barrus,
// Morley, Shirley, "An efficient and robust ray-box intersection algorithm"
// (2005): near/far planes chosen by the sign of 1/d; each plane's distance
// one fma, p * (1/d) - o * (1/d), the offset moved by a margin that keeps
// the interval around the exact one (SlabTerms; a zero d as +-2^-80); a NaN
// distance is dropped by the order of the min/max operands. The interval is
// widened by kSlabSlack relative (beyond Ize's 2 gamma(3), "Robust BVH ray
// traversal", JCGT 2013, to cover the kernels' own error in t), so no
// primitive a brute-force scan reports is culled. Rays whose terms allow it
// compare the distances by their bits, as integers (Embree's form, with
// shorter latencies): widened_interval_bits. The widening is relative, so
// it would narrow negative distances: a ray whose interval reaches behind
// its origin (tmin < 0) enters every child (geometry/bvh/node_ray.h).
#pragma once

#include <array>

#include "geometry/box.h"
#include "geometry/bvh.h"
#include "simd/lanes.h"

namespace quiver {

// Relative widening of every slab interval: 2^-10, above the relative t
// error of every kernel in the stability tests.
inline constexpr float kSlabSlack = 0x1p-10f;

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

inline namespace QUIVER_UNIT_NAMESPACE {

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
// 2^-22 |o| and by 2^-40.
template <class F>
struct SlabTerms {
  F entry_inv_dir, entry_offset, exit_inv_dir, exit_offset;  // offsets negated

  [[gnu::always_inline]] static SlabTerms of(const F& origin, const F& direction) {
    const F tiny(0x1p-80f);
    const Mask<F> zero = abs(direction) < tiny;
    const F inv = F(1.f) / select(zero, copysign(tiny, direction), direction);
    const F offset = origin * inv;
    // A zero d's slab also widened by 2^-40 absolute (2^40 in t): a ray lying
    // on a face at 0 (where 2^-22 |o| is 0) would else leave it at t = 0.
    const F margin = F(0x1p-22f) * abs(offset) + select(zero, F(0x1p40f), F(0.f));
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

// The lanes of `active` whose ray may meet `box` within [tmin, tmax]: the
// node tests' widened interval, each lane's planes chosen by its own signs;
// a lane whose interval reaches behind its origin (tmin < 0) always may, as
// such a ray enters every node. Conservative as the node tests are, so
// skipping the other lanes culls no hit of the box's primitives.
template <class F>
inline Mask<F> may_meet_box(const Ray<F>& ray, const Box& box, const Mask<F>& active, const F& tmax) {
  std::array<F, 3> entry, exit;
  for (int a = 0; a < 3; ++a) {
    const SlabTerms<F> terms = SlabTerms<F>::of(ray.origin[a], ray.direction[a]);
    const Mask<F> negative = terms.entry_inv_dir < F(0.f);
    entry[a] = terms.entry(select(negative, F(box.hi[a]), F(box.lo[a])));
    exit[a] = terms.widened_exit(select(negative, F(box.lo[a]), F(box.hi[a])));
  }
  F near;
  return active && (widened_interval(entry, exit, ray.tmin, tmax, near) || ray.tmin < F(0.f));
}

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

}  // namespace QUIVER_UNIT_NAMESPACE
}  // namespace quiver
