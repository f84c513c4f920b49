// Streams: the loops that drive one kernel over many rays and a whole
// primitive store, written once for every width, in the two orientations
// (geometry/leaf_loops.h):
//   packets: W rays against one primitive at a time (primitive broadcast);
//   scan:    one ray against W primitives at a time (ray broadcast), the
//            block's nearest hit kept.
// Closest hits are the smallest (t, id), as in the BVH walks. The packet
// loops _within a box first test each packet against it (may_meet_box,
// geometry/bvh/slab.h: as conservative as a BVH node), the cull of a store
// scanned without a BVH.
//
// A Method is a struct with
//   template <class F> static R prepare(const Ray<F>&);   per-ray setup, hoisted
//       out of the primitive loop (derive from RayAsIs when there is none);
//   template <class F, class P> static Mask<F> intersect(
//       const R& prepared, const P& prim, const F& tmax, const Mask<F>& active,
//       Candidate<F>& out);
// returning the lanes that hit within (ray.tmin, tmax), never an inactive
// lane. out.t depends on the ray, the primitive and tmin only; tmax only
// accepts or rejects (so the scan and packet orders agree bit for bit).
// A primitive store S has size(), broadcast<F>(i), load<F>(first) and
// id_base: a hit on primitive i reports id id_base + i.
// Branches only where no lane can be affected: a closest-hit commit is
// skipped when no lane is closer, any-hit stops when every lane is blocked.
//
// Each kind's <kind>_streams.cpp is compiled once per kernel unit and
// instantiates these loops for it, in the unit's namespace
// (simd/kernel_units.h); the loops are flattened. The product instantiates
// what quiver runs: its methods, packets only, BVH node width
// kProductNodeWidth; the alternatives the tests, benchmarks and accuracy
// study compare are instantiated in tests/support/study_streams.cpp.
#pragma once

#include <cstddef>
#include <limits>
#include <type_traits>

#include "geometry/box.h"
#include "geometry/bvh/slab.h"
#include "geometry/leaf_loops.h"
#include "geometry/method_error.h"
#include "geometry/soa.h"

namespace quiver {

template <class S>
struct KernelStreams {
  void (*closest_packets)(const RaySoA&, const S&, HitSoA&) = nullptr;
  void (*occluded_packets)(const RaySoA&, const S&, OcclusionSoA&) = nullptr;
  // The same, skipping each packet whose rays all pass by `bounds`, a box
  // of every primitive of the store (primitive_box): a scanned store's cull.
  void (*closest_packets_within)(const RaySoA&, const S&, const Box& bounds, HitSoA&) = nullptr;
  void (*occluded_packets_within)(const RaySoA&, const S&, const Box& bounds, OcclusionSoA&) = nullptr;
  // nullptr in the product, which runs packets, and where a kind has no
  // scan orientation (it does not pay).
  void (*closest_scan)(const RaySoA&, const S&, HitSoA&) = nullptr;
  void (*occluded_scan)(const RaySoA&, const S&, OcclusionSoA&) = nullptr;
};

inline namespace QUIVER_UNIT_NAMESPACE {

// Packets of rays against every primitive; with bounds, a packet none of
// whose active rays may meet them (may_meet_box, before the nearest hit so
// far) is skipped.
template <KernelUnit U, class Method, class S>
[[gnu::flatten]] void closest_packets_culled(const RaySoA& rays, const S& prims, const Box* bounds, HitSoA& hits) {
  using F = UnitLanes<U>;
  constexpr std::size_t W = lane_count<F>;
  for (std::size_t first = 0; first < rays.count; first += W) {
    const Mask<F> active = first_lanes<F>(rays.count - first);
    const Ray<F> ray = rays.load<F>(first);
    Hit<F> hit = hits.load<F>(first);
    if (bounds != nullptr && none(may_meet_box(ray, *bounds, active, next_float_up(hit.t)))) continue;
    const auto prepared = Method::prepare(ray);
    closest_one_by_one<F>(MethodTest<Method, decltype(prepared)>{prepared}, prims, 0, prims.size(), active, hit);
    hits.store(first, hit);
  }
}

template <KernelUnit U, class Method, class S>
[[gnu::flatten]] void occluded_packets_culled(const RaySoA& rays, const S& prims, const Box* bounds,
                                              OcclusionSoA& result) {
  using F = UnitLanes<U>;
  constexpr std::size_t W = lane_count<F>;
  for (std::size_t first = 0; first < rays.count; first += W) {
    const Ray<F> ray = rays.load<F>(first);
    const Mask<F> valid = first_lanes<F>(rays.count - first);
    if (bounds != nullptr && none(may_meet_box(ray, *bounds, valid, ray.tmax))) continue;
    const auto prepared = Method::prepare(ray);
    const Mask<F> occluded = occluded_one_by_one<F>(MethodTest<Method, decltype(prepared)>{prepared}, prims, 0,
                                                    prims.size(), valid, ray.tmax,
                                                    nonzero_lanes(load_int_lanes<F>(result.occluded.data() + first)) &&
                                                        valid);
    store_int_lanes<F>(select(occluded, IntLanes<F>(1), IntLanes<F>(0)), result.occluded.data() + first);
  }
}

template <KernelUnit U, class Method, class S>
void closest_packets(const RaySoA& rays, const S& prims, HitSoA& hits) {
  closest_packets_culled<U, Method, S>(rays, prims, nullptr, hits);
}
template <KernelUnit U, class Method, class S>
void occluded_packets(const RaySoA& rays, const S& prims, OcclusionSoA& result) {
  occluded_packets_culled<U, Method, S>(rays, prims, nullptr, result);
}
template <KernelUnit U, class Method, class S>
void closest_packets_within(const RaySoA& rays, const S& prims, const Box& bounds, HitSoA& hits) {
  closest_packets_culled<U, Method, S>(rays, prims, &bounds, hits);
}
template <KernelUnit U, class Method, class S>
void occluded_packets_within(const RaySoA& rays, const S& prims, const Box& bounds, OcclusionSoA& result) {
  occluded_packets_culled<U, Method, S>(rays, prims, &bounds, result);
}

template <KernelUnit U, class Method, class S>
[[gnu::flatten]] void closest_scan(const RaySoA& rays, const S& prims, HitSoA& hits) {
  using F = UnitLanes<U>;
  for (std::size_t r = 0; r < rays.count; ++r) {
    const auto prepared = Method::prepare(broadcast_ray<F>(rays.get(r)));
    Hit<float> hit = hits.get(r);
    closest_by_blocks<F>(MethodTest<Method, decltype(prepared)>{prepared}, prims, 0, prims.size(), hit);
    hits.set(r, hit);
  }
}

template <KernelUnit U, class Method, class S>
[[gnu::flatten]] void occluded_scan(const RaySoA& rays, const S& prims, OcclusionSoA& result) {
  using F = UnitLanes<U>;
  for (std::size_t r = 0; r < rays.count; ++r) {
    if (result.occluded[r] != 0) continue;
    const Ray<float> ray = rays.get(r);
    const auto prepared = Method::prepare(broadcast_ray<F>(ray));
    if (occluded_by_blocks<F>(MethodTest<Method, decltype(prepared)>{prepared}, prims, 0, prims.size(), ray.tmax)) {
      result.occluded[r] = 1;
    }
  }
}

// The four streams of one method in kernel unit U.
template <KernelUnit U, class Method, class S>
KernelStreams<S> make_streams() {
  KernelStreams<S> s;
  s.closest_packets = &closest_packets<U, Method, S>;
  s.occluded_packets = &occluded_packets<U, Method, S>;
  s.closest_packets_within = &closest_packets_within<U, Method, S>;
  s.occluded_packets_within = &occluded_packets_within<U, Method, S>;
  s.closest_scan = &closest_scan<U, Method, S>;
  s.occluded_scan = &occluded_scan<U, Method, S>;
  return s;
}

// Packets only: what the product runs, and all a kind without a scan
// orientation has.
template <KernelUnit U, class Method, class S>
KernelStreams<S> make_packet_streams() {
  KernelStreams<S> s;
  s.closest_packets = &closest_packets<U, Method, S>;
  s.occluded_packets = &occluded_packets<U, Method, S>;
  s.closest_packets_within = &closest_packets_within<U, Method, S>;
  s.occluded_packets_within = &occluded_packets_within<U, Method, S>;
  return s;
}

}  // namespace QUIVER_UNIT_NAMESPACE
}  // namespace quiver
