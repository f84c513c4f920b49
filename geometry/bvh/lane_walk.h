// A packet's rays walked one by one with the packet's setup done at once:
// the node terms (LaneNodeTerms) and the method's frames
// (Method::prepare_lanes) for every lane in SIMD, then the rays walked
// frame by frame through the single-ray walks; lanes the terms do not cover
// walk alone from their own setup.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "geometry/bvh/single_walk.h"

namespace quiver {
inline namespace QUIVER_UNIT_NAMESPACE {

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

  explicit LaneHits(const Hit<F>& hit) { store_column_hits(*this, 0, hit); }
  Hit<float> get(std::size_t k) const { return column_hit(*this, k); }
  void set(std::size_t k, const Hit<float>& hit) { set_column_hit(*this, k, hit); }
  Hit<F> packet() const { return load_column_hits<F>(*this, 0); }
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
// pays for its own divisions and frame branches (a ray with few node
// visits would spend most of its walk on that setup); a lane those terms
// do not cover walks through closest_bvh_single. Out of line and
// flattened, as closest_bvh_single.
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

}  // namespace QUIVER_UNIT_NAMESPACE
}  // namespace quiver
