// Candidate<F>: what a kernel reports for one primitive; Hit<F>: the closest
// so far. ng is the geometric normal, not necessarily unit length, oriented
// by the primitive (not flipped toward the ray). u, v are the kernel's
// surface parameters (barycentrics for triangles, see each kernel).
#pragma once

#include <cstddef>
#include <cstdint>

#include "simd/lanes.h"

namespace quiver {

inline constexpr std::int32_t kNoHit = -1;

template <class F>
struct Candidate {
  F t, u, v;
  Vec3<F> ng;
};

template <class F>
struct Hit {
  F t, u, v;
  Vec3<F> ng;
  IntLanes<F> id;

  [[gnu::always_inline]] static Hit none(const F& tmax) {
    return {tmax, F(0.f), F(0.f), Vec3<F>(F(0.f), F(0.f), F(0.f)), IntLanes<F>(kNoHit)};
  }

  // Takes the candidate in lanes where `closer` is set.
  [[gnu::always_inline]] void commit(const Mask<F>& closer, const Candidate<F>& c, const IntLanes<F>& prim) {
    t = select(closer, c.t, t);
    u = select(closer, c.u, u);
    v = select(closer, c.v, v);
    ng = select(closer, c.ng, ng);
    id = select(closer, prim, id);
  }
};

inline namespace QUIVER_UNIT_NAMESPACE {

// Early exit of a kernel once no lane can hit: zeroes the candidate (so no
// lane carries unset values) and returns the all-false mask it is given.
template <class F>
inline Mask<F> no_hit(const Mask<F>& no_lane, Candidate<F>& out) {
  out.t = F(0.f);
  out.u = F(0.f);
  out.v = F(0.f);
  out.ng = Vec3<F>(F(0.f), F(0.f), F(0.f));
  return no_lane;
}

// Hits kept as columns: any type with t, u, v, ngx, ngy, ngz (floats) and
// id (int32) arrays, as HitSoA and a lane walk's LaneHits. Hit k, and the
// packet of hits starting at `first` (aligned).
template <class Columns>
[[gnu::always_inline]] inline Hit<float> column_hit(const Columns& c, std::size_t k) {
  return {c.t[k], c.u[k], c.v[k], {c.ngx[k], c.ngy[k], c.ngz[k]}, c.id[k]};
}

template <class Columns>
[[gnu::always_inline]] inline void set_column_hit(Columns& c, std::size_t k, const Hit<float>& hit) {
  c.t[k] = hit.t;
  c.u[k] = hit.u;
  c.v[k] = hit.v;
  c.ngx[k] = hit.ng.x;
  c.ngy[k] = hit.ng.y;
  c.ngz[k] = hit.ng.z;
  c.id[k] = hit.id;
}

template <class F, class Columns>
[[gnu::always_inline]] inline Hit<F> load_column_hits(const Columns& c, std::size_t first) {
  return {load_lanes<F>(c.t.data() + first),
          load_lanes<F>(c.u.data() + first),
          load_lanes<F>(c.v.data() + first),
          Vec3<F>(load_lanes<F>(c.ngx.data() + first), load_lanes<F>(c.ngy.data() + first),
                  load_lanes<F>(c.ngz.data() + first)),
          load_int_lanes<F>(c.id.data() + first)};
}

template <class F, class Columns>
[[gnu::always_inline]] inline void store_column_hits(Columns& c, std::size_t first, const Hit<F>& hit) {
  store_lanes(hit.t, c.t.data() + first);
  store_lanes(hit.u, c.u.data() + first);
  store_lanes(hit.v, c.v.data() + first);
  store_lanes(hit.ng.x, c.ngx.data() + first);
  store_lanes(hit.ng.y, c.ngy.data() + first);
  store_lanes(hit.ng.z, c.ngz.data() + first);
  store_int_lanes<F>(hit.id, c.id.data() + first);
}

}  // namespace QUIVER_UNIT_NAMESPACE
}  // namespace quiver
