// Two float sequences hold the same bits: the same length and every value
// bit for bit (signed zeros and NaNs included), as tests say that two
// builds or two renders are identical.
#pragma once

#include <cstring>
#include <span>

namespace quiver::testing {

inline bool same_bits(std::span<const float> a, std::span<const float> b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size_bytes()) == 0);
}

}  // namespace quiver::testing
