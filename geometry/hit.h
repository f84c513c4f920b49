// Candidate<F>: what a kernel reports for one primitive; Hit<F>: the closest
// so far. ng is the geometric normal, not necessarily unit length, oriented
// by the primitive (not flipped toward the ray). u, v are the kernel's
// surface parameters (barycentrics for triangles, see each kernel).
#pragma once

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

  static Hit none(const F& tmax) {
    return {tmax, F(0.f), F(0.f), Vec3<F>(F(0.f), F(0.f), F(0.f)), IntLanes<F>(kNoHit)};
  }

  // Takes the candidate in lanes where `closer` is set.
  void commit(const Mask<F>& closer, const Candidate<F>& c, const IntLanes<F>& prim) {
    t = select(closer, c.t, t);
    u = select(closer, c.u, u);
    v = select(closer, c.v, v);
    ng = select(closer, c.ng, ng);
    id = select(closer, prim, id);
  }
};

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

}  // namespace quiver
