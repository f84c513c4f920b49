// Streams: the loops that drive one kernel over many rays and primitives,
// written once for every width, in the two orientations:
//   packets: W rays against one primitive at a time (primitive broadcast);
//   scan:    one ray against W primitives at a time (ray broadcast), then the
//            closest lane wins (smallest t, then smallest id, as the scalar
//            loop's strict '<' keeps the first of equal hits).
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
// instantiates these loops for it. The unit is a template argument, so the
// two float units (scalar, scalar_fma) get distinct symbols, and the loops are
// flattened, so no kernel code leaves them as a shared out-of-line copy
// (tests/geometry_streams_unit_symbols_test.cmake checks the objects).
#pragma once

#include <cstddef>
#include <limits>
#include <type_traits>

#include "geometry/soa.h"

namespace quiver {

template <class S>
struct KernelStreams {
  void (*closest_packets)(const RaySoA&, const S&, HitSoA&) = nullptr;
  void (*occluded_packets)(const RaySoA&, const S&, OcclusionSoA&) = nullptr;
  // nullptr where a kind has no scan orientation (it does not pay).
  void (*closest_scan)(const RaySoA&, const S&, HitSoA&) = nullptr;
  void (*occluded_scan)(const RaySoA&, const S&, OcclusionSoA&) = nullptr;
};

#ifdef QUIVER_KERNEL_UNIT
// The unit this translation unit is compiled for (CMake defines the name).
constexpr KernelUnit kThisUnit = KernelUnit::QUIVER_KERNEL_UNIT;
#endif

template <KernelUnit U>
using Unit = std::integral_constant<KernelUnit, U>;

// Calls fn(Unit<U>{}) for a run-time kernel unit.
template <class Fn>
decltype(auto) with_kernel_unit(KernelUnit unit, Fn&& fn) {
  switch (unit) {
    case KernelUnit::avx512: return fn(Unit<KernelUnit::avx512>{});
    case KernelUnit::avx2: return fn(Unit<KernelUnit::avx2>{});
    case KernelUnit::sse4: return fn(Unit<KernelUnit::sse4>{});
    case KernelUnit::scalar_fma: return fn(Unit<KernelUnit::scalar_fma>{});
    case KernelUnit::scalar: break;
  }
  return fn(Unit<KernelUnit::scalar>{});
}

template <KernelUnit U, class Method, class S>
[[gnu::flatten]] void closest_packets(const RaySoA& rays, const S& prims, HitSoA& hits) {
  using F = UnitLanes<U>;
  constexpr std::size_t W = lane_count<F>;
  for (std::size_t first = 0; first < rays.count; first += W) {
    const Mask<F> active = first_lanes<F>(rays.count - first);
    const Ray<F> ray = rays.load<F>(first);
    const auto prepared = Method::prepare(ray);
    Hit<F> hit = hits.load<F>(first);
    for (std::size_t p = 0; p < prims.size(); ++p) {
      Candidate<F> c;
      const Mask<F> closer = Method::intersect(prepared, prims.template broadcast<F>(p), hit.t, active, c);
      if (any(closer)) hit.commit(closer, c, IntLanes<F>(prims.id_base + static_cast<std::int32_t>(p)));
    }
    hits.store(first, hit);
  }
}

template <KernelUnit U, class Method, class S>
[[gnu::flatten]] void occluded_packets(const RaySoA& rays, const S& prims, OcclusionSoA& result) {
  using F = UnitLanes<U>;
  constexpr std::size_t W = lane_count<F>;
  for (std::size_t first = 0; first < rays.count; first += W) {
    const Ray<F> ray = rays.load<F>(first);
    const auto prepared = Method::prepare(ray);
    const Mask<F> valid = first_lanes<F>(rays.count - first);
    Mask<F> occluded = nonzero_lanes(load_int_lanes<F>(result.occluded.data() + first)) && valid;
    for (std::size_t p = 0; p < prims.size(); ++p) {
      const Mask<F> active = and_not(valid, occluded);
      if (none(active)) break;
      Candidate<F> unused;
      occluded = occluded || Method::intersect(prepared, prims.template broadcast<F>(p), ray.tmax, active, unused);
    }
    store_int_lanes<F>(select(occluded, IntLanes<F>(1), IntLanes<F>(0)), result.occluded.data() + first);
  }
}

// The lanes of `lanes` at the smallest t among them (their t < +inf), by
// one vector reduction: a loop over the lanes, unrolled in every watertight
// frame's copy of the single-ray walk, had made that walk twice its size
// and slower (bench/README.md).
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

// The closest of a lane set's hits; ties go to the smaller id.
template <class F>
[[gnu::always_inline]] inline Hit<float> closest_lane(const Hit<F>& hit, float tmax) {
  if constexpr (lane_count<F> == 1) {
    return hit;
  } else {
    const Mask<F> hit_lanes = int_less(IntLanes<F>(kNoHit), hit.id);  // ids are >= 0
    if (none(hit_lanes)) return Hit<float>::none(tmax);
    unsigned at_nearest = nearest_lanes(hit_lanes, hit.t);
    alignas(64) std::int32_t id[kMaxLanes];
    store_int_lanes<F>(hit.id, id);
    int best = __builtin_ctz(at_nearest);
    for (at_nearest &= at_nearest - 1; at_nearest != 0; at_nearest &= at_nearest - 1) {
      const int lane = __builtin_ctz(at_nearest);
      if (id[lane] < id[best]) best = lane;
    }
    return {lane_value(hit.t, best),
            lane_value(hit.u, best),
            lane_value(hit.v, best),
            {lane_value(hit.ng.x, best), lane_value(hit.ng.y, best), lane_value(hit.ng.z, best)},
            id[best]};
  }
}

template <KernelUnit U, class Method, class S>
[[gnu::flatten]] void closest_scan(const RaySoA& rays, const S& prims, HitSoA& hits) {
  using F = UnitLanes<U>;
  constexpr std::size_t W = lane_count<F>;
  for (std::size_t r = 0; r < rays.count; ++r) {
    const Ray<F> ray = broadcast_ray<F>(rays.get(r));
    const auto prepared = Method::prepare(ray);
    const Hit<float> before = hits.get(r);
    Hit<F> best = Hit<F>::none(F(before.t));
    bool committed = false;  // the lane reduction only for rays that hit
    for (std::size_t first = 0; first < prims.size(); first += W) {
      Candidate<F> c;
      const Mask<F> active = first_lanes<F>(prims.size() - first);
      const Mask<F> closer = Method::intersect(prepared, prims.template load<F>(first), best.t, active, c);
      if (any(closer)) {
        best.commit(closer, c, IntLanes<F>(prims.id_base + static_cast<std::int32_t>(first)) + lane_index<F>());
        committed = true;
      }
    }
    if (!committed) continue;
    const Hit<float> found = closest_lane(best, before.t);
    if (found.id != kNoHit) hits.set(r, found);
  }
}

template <KernelUnit U, class Method, class S>
[[gnu::flatten]] void occluded_scan(const RaySoA& rays, const S& prims, OcclusionSoA& result) {
  using F = UnitLanes<U>;
  constexpr std::size_t W = lane_count<F>;
  for (std::size_t r = 0; r < rays.count; ++r) {
    if (result.occluded[r] != 0) continue;
    const Ray<F> ray = broadcast_ray<F>(rays.get(r));
    const auto prepared = Method::prepare(ray);
    for (std::size_t first = 0; first < prims.size(); first += W) {
      Candidate<F> unused;
      const Mask<F> active = first_lanes<F>(prims.size() - first);
      if (any(Method::intersect(prepared, prims.template load<F>(first), ray.tmax, active, unused))) {
        result.occluded[r] = 1;
        break;
      }
    }
  }
}

// The four streams of one method in kernel unit U.
template <KernelUnit U, class Method, class S>
KernelStreams<S> make_streams() {
  KernelStreams<S> s;
  s.closest_packets = &closest_packets<U, Method, S>;
  s.occluded_packets = &occluded_packets<U, Method, S>;
  s.closest_scan = &closest_scan<U, Method, S>;
  s.occluded_scan = &occluded_scan<U, Method, S>;
  return s;
}

// Packets only, for kinds whose scan orientation does not pay.
template <KernelUnit U, class Method, class S>
KernelStreams<S> make_packet_streams() {
  KernelStreams<S> s;
  s.closest_packets = &closest_packets<U, Method, S>;
  s.occluded_packets = &occluded_packets<U, Method, S>;
  return s;
}

}  // namespace quiver
