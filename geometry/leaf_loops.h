// The loops that test rays against a run of primitives [first, end) of one
// store, written once for the streams (a whole store) and the BVH walks (a
// leaf), in both orientations:
//   one by one: W rays (a packet, or one ray as F = float) against one
//               primitive at a time (the store's broadcast<F>);
//   by blocks:  one ray against W primitives at a time (the store's
//               load<F>), the block's nearest hit kept.
// Closest hit: the lexicographic minimum of (t, id): the test gets tmax =
// next_float_up(t) and a hit at exactly t wins only with a smaller id, so
// the result does not depend on the order in which runs are visited, nor
// on the width. Any hit: occlusion within (tmin, tmax); a run stops when
// every lane is blocked. A test is an object with
//   Mask<F> intersect(const P& prim, const F& tmax, const Mask<F>& active, Candidate<F>& out)
// (MethodTest: a method's intersect on its prepared rays).
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>

#include "geometry/hit.h"

namespace quiver {
inline namespace QUIVER_UNIT_NAMESPACE {

// A method's test of a prepared ray or packet.
template <class Method, class Prepared>
struct MethodTest {
  const Prepared& prepared;

  template <class P, class F>
  [[gnu::always_inline]] Mask<F> intersect(const P& prim, const F& tmax, const Mask<F>& active,
                                           Candidate<F>& out) const {
    return Method::intersect(prepared, prim, tmax, active, out);
  }
};

// The closest-hit rule: a candidate at exactly the current t wins only with a smaller id.
template <class F>
inline Mask<F> wins_over(const Mask<F>& hit, const F& t, const IntLanes<F>& id, const Hit<F>& best) {
  return hit && (t < best.t || (t == best.t && int_less(id, best.id)));
}

// The lanes of `lanes` at the smallest t among them (their t < +inf), by
// one vector reduction, not a loop over the lanes unrolled in each of the
// single-ray walk's frame copies, so those copies stay small.
template <class F>
[[gnu::always_inline]] inline unsigned nearest_lanes(const Mask<F>& lanes, const F& t) {
  const F t_in = select(lanes, t, F(std::numeric_limits<float>::infinity()));
  return lane_bits(lanes && t_in == F(horizontal_min(t_in)));
}

// One lane's value.
template <class F>
[[gnu::always_inline]] inline float lane_value(const F& v, int lane) {
  alignas(64) float values[kMaxLanes];
  store_lanes(v, values);
  return values[lane];
}

// One lane of a candidate as a hit on primitive `id`.
template <class F>
[[gnu::always_inline]] inline Hit<float> lane_hit(const Candidate<F>& c, int lane, std::int32_t id) {
  return {lane_value(c.t, lane),
          lane_value(c.u, lane),
          lane_value(c.v, lane),
          {lane_value(c.ng.x, lane), lane_value(c.ng.y, lane), lane_value(c.ng.z, lane)},
          id};
}

// Rays (the lanes of `lanes`) against primitives [first, end), one at a
// time. Returns whether some lane's closest hit changed.
template <class F, class Test, class S>
[[gnu::always_inline]] inline bool closest_one_by_one(const Test& test, const S& prims, std::size_t first,
                                                      std::size_t end, const Mask<F>& lanes, Hit<F>& hit) {
  bool changed = false;
  for (std::size_t p = first; p < end; ++p) {
    Candidate<F> c;
    const Mask<F> hits_p = test.intersect(prims.template broadcast<F>(p), next_float_up(hit.t), lanes, c);
    const IntLanes<F> id(prims.id_base + static_cast<std::int32_t>(p));
    const Mask<F> closer = wins_over(hits_p, c.t, id, hit);
    if (any(closer)) {
      hit.commit(closer, c, id);
      changed = true;
    }
  }
  return changed;
}

// Rays (the lanes of `lanes`) against primitives [first, end), one at a
// time, until every lane is blocked within (tmin, tmax): the blocked lanes,
// those blocked on entry included.
template <class F, class Test, class S>
[[gnu::always_inline]] inline Mask<F> occluded_one_by_one(const Test& test, const S& prims, std::size_t first,
                                                          std::size_t end, const Mask<F>& lanes, const F& tmax,
                                                          Mask<F> occluded) {
  for (std::size_t p = first; p < end; ++p) {
    const Mask<F> open = and_not(lanes, occluded);
    if (none(open)) break;
    Candidate<F> unused;
    occluded = occluded || test.intersect(prims.template broadcast<F>(p), tmax, open, unused);
  }
  return occluded;
}

// One ray (broadcast to F's lanes in the test) against primitives [first,
// end) in blocks of W. Ids rise with the lane, so of a block's nearest hits
// the lowest lane has the smallest id.
template <class F, class Test, class S>
[[gnu::always_inline]] inline void closest_by_blocks(const Test& test, const S& prims, std::size_t first,
                                                     std::size_t end, Hit<float>& hit) {
  for (std::size_t block = first; block < end; block += lane_count<F>) {
    Candidate<F> c;
    const Mask<F> hits_block =
        test.intersect(prims.template load<F>(block), F(next_float_up(hit.t)), first_lanes<F>(end - block), c);
    if (none(hits_block)) continue;
    const int lane = __builtin_ctz(nearest_lanes(hits_block, c.t));
    const std::int32_t id = prims.id_base + static_cast<std::int32_t>(block) + lane;
    if (wins_over(true, lane_value(c.t, lane), id, hit)) hit = lane_hit(c, lane, id);
  }
}

// One ray against primitives [first, end) in blocks of W: whether any
// blocks it within (tmin, tmax).
template <class F, class Test, class S>
[[gnu::always_inline]] inline bool occluded_by_blocks(const Test& test, const S& prims, std::size_t first,
                                                      std::size_t end, float tmax) {
  for (std::size_t block = first; block < end; block += lane_count<F>) {
    Candidate<F> unused;
    if (any(test.intersect(prims.template load<F>(block), F(tmax), first_lanes<F>(end - block), unused))) {
      return true;
    }
  }
  return false;
}

}  // namespace QUIVER_UNIT_NAMESPACE
}  // namespace quiver
