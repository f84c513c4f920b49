// What a primitive builder kept and what it dropped, and why. Builders never
// put NaN, Inf or a degenerate primitive into the SoA arrays.
#pragma once

#include <cstddef>

namespace quiver {

struct BuildReport {
  std::size_t kept = 0;
  std::size_t dropped_non_finite = 0;  // NaN or Inf in any input number
  std::size_t dropped_degenerate = 0;  // zero area, zero radius, not planar, ...

  std::size_t dropped() const { return dropped_non_finite + dropped_degenerate; }
};

}  // namespace quiver
