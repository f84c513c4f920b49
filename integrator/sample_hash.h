// Random numbers as hashes, so a sample's numbers depend only on what
// identifies it (its film point, the light, the dimension) and never on
// the width, tile or thread that computes it: SplitMix64's finaliser
// (Steele, Lea and Flood, "Fast splittable pseudorandom number
// generators", OOPSLA 2014) over the key and the indices.
#pragma once

#include <bit>
#include <cstdint>

#include "simd/kernel_units.h"

namespace quiver {

inline namespace QUIVER_UNIT_NAMESPACE {

inline std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// A key for the camera sample at film point (x, y) (same point, same key).
inline std::uint64_t sample_key(double x, double y, std::uint64_t seed) {
  return mix64(mix64(mix64(seed) ^ std::bit_cast<std::uint64_t>(x)) ^ std::bit_cast<std::uint64_t>(y));
}

// A uniform number in [0, 1) from a key and two indices.
inline float hash_uniform(std::uint64_t key, std::uint64_t a, std::uint64_t b) {
  const std::uint64_t h = mix64(mix64(key ^ mix64(a + 0x9e3779b97f4a7c15ULL)) ^ b);
  return float(h >> 40) * 0x1p-24f;  // 24 bits: exactly representable, < 1
}

}  // namespace QUIVER_UNIT_NAMESPACE
}  // namespace quiver
