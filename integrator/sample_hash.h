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

// The numbers a key and an index a open: number b of them is
// stream_uniform(hash_stream(key, a), b), so a caller drawing several b
// for one (key, a) hashes the pair once.
inline std::uint64_t hash_stream(std::uint64_t key, std::uint64_t a) {
  return mix64(key ^ mix64(a + 0x9e3779b97f4a7c15ULL));
}

// Number b of a stream: uniform in [0, 1).
inline float stream_uniform(std::uint64_t stream, std::uint64_t b) {
  return float(mix64(stream ^ b) >> 40) * 0x1p-24f;  // 24 bits: exactly representable, < 1
}

// A uniform number in [0, 1) from a key and two indices.
inline float hash_uniform(std::uint64_t key, std::uint64_t a, std::uint64_t b) {
  return stream_uniform(hash_stream(key, a), b);
}

}  // namespace QUIVER_UNIT_NAMESPACE
}  // namespace quiver
