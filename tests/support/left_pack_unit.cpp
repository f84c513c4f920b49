// Compiled once per kernel unit (tests/CMakeLists.txt): see left_pack_units.h.
#include <array>
#include <cstdint>
#include <string>

#include "simd/lanes.h"
#include "tests/support/left_pack_units.h"

namespace quiver::testing {

inline namespace QUIVER_UNIT_NAMESPACE {
namespace {

std::string check_every_mask() {
  using F = UnitLanes<kThisUnit>;
  constexpr int W = lane_count<F>;
  constexpr float kUnwritten = -1.f;
  alignas(64) std::array<float, W> a{}, b{};
  alignas(64) std::array<std::int32_t, W> n{};
  for (int k = 0; k < W; ++k) {
    a[std::size_t(k)] = float(k);
    b[std::size_t(k)] = float(100 + k);
    n[std::size_t(k)] = 1000 + k;
  }
  for (unsigned mask = 0; mask < (1u << W); ++mask) {
    std::array<float, W + 1> to_a, to_b;
    std::array<std::int32_t, W + 1> to_n;
    to_a.fill(kUnwritten);
    to_b.fill(kUnwritten);
    to_n.fill(-1);
    // Destinations one element into their arrays: unaligned, as the columns are.
    store_selected_lanes<F, 2, 1>(mask, {load_lanes<F>(a.data()), load_lanes<F>(b.data())},
                                  {to_a.data() + 1, to_b.data() + 1}, {load_int_lanes<F>(n.data())},
                                  {to_n.data() + 1});
    const std::string at = "mask " + std::to_string(mask) + ": ";
    if (to_a[0] != kUnwritten || to_b[0] != kUnwritten || to_n[0] != -1) return at + "wrote before the start";
    std::size_t i = 1;
    for (int k = 0; k < W; ++k) {
      if ((mask >> k & 1u) == 0) continue;
      if (to_a[i] != float(k) || to_b[i] != float(100 + k) || to_n[i] != 1000 + k) {
        return at + "slot " + std::to_string(i - 1) + " does not hold lane " + std::to_string(k);
      }
      ++i;
    }
    for (; i < to_a.size(); ++i) {
      if (to_a[i] != kUnwritten || to_b[i] != kUnwritten || to_n[i] != -1) {
        return at + "wrote past its set lanes, at slot " + std::to_string(i - 1);
      }
    }
  }
  return "";
}

}  // namespace
}  // namespace QUIVER_UNIT_NAMESPACE

template <>
std::string left_pack_every_mask<kThisUnit>() {
  return check_every_mask();
}

}  // namespace quiver::testing
