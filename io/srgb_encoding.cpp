#include "io/srgb_encoding.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <vector>

namespace quiver {

namespace {

// thresholds[k] (k = 1..255): the smallest float whose code is at least k;
// thresholds[0] = -infinity, below every value.
std::array<float, 256> code_thresholds() {
  std::array<float, 256> thresholds{};
  thresholds[0] = -std::numeric_limits<float>::infinity();
  for (int k = 1; k <= 255; ++k) {
    // Non-negative floats order as their bit patterns; code(1) = 255 >= k.
    std::uint32_t low = 0, high = std::bit_cast<std::uint32_t>(1.f);
    while (low < high) {
      const std::uint32_t middle = low + (high - low) / 2;
      if (srgb_byte_formula(std::bit_cast<float>(middle)) >= k) {
        high = middle;
      } else {
        low = middle + 1;
      }
    }
    thresholds[std::size_t(k)] = std::bit_cast<float>(low);
  }
  return thresholds;
}

}  // namespace

std::uint8_t srgb_byte_formula(float linear) {
  const double c = std::isnan(linear) ? 0.0 : std::clamp(double(linear), 0.0, 1.0);
  const double encoded = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
  return static_cast<std::uint8_t>(std::clamp(std::floor(encoded * 255.0 + 0.5), 0.0, 255.0));
}

namespace {

// Where the lookup starts: the code of the lowest float of each bucket of
// the floats in [0, 1) that share their top 16 bits (exponent and 7 bits of
// mantissa). No bucket's codes differ by more than one, so the lookup
// takes at most one step from its start.
constexpr std::uint32_t kBucketShift = 16;

struct CodeTables {
  std::array<float, 256> thresholds;
  std::vector<std::uint8_t> bucket_code;

  CodeTables() : thresholds(code_thresholds()) {
    const std::uint32_t buckets = std::bit_cast<std::uint32_t>(1.f) >> kBucketShift;
    bucket_code.resize(buckets);
    std::uint8_t k = 0;
    for (std::uint32_t b = 0; b < buckets; ++b) {
      const float lowest = std::bit_cast<float>(b << kBucketShift);
      while (k < 255 && thresholds[std::size_t(k) + 1] <= lowest) ++k;
      bucket_code[b] = k;
    }
  }
};

const CodeTables& code_tables() {
  static const CodeTables tables;
  return tables;
}

std::uint8_t code_of(const CodeTables& tables, float linear) {
  // NaN, negatives and 0 are code 0; 1 and above 255.
  if (!(linear > 0.f)) return 0;
  if (!(linear < 1.f)) return 255;
  // The largest k with thresholds[k] <= linear, from its bucket's code: the
  // one step a bucket may hold without a branch, the loop for any further.
  std::size_t k = tables.bucket_code[std::bit_cast<std::uint32_t>(linear) >> kBucketShift];
  k += k < 255 && tables.thresholds[k + 1] <= linear ? 1 : 0;
  while (k < 255 && tables.thresholds[k + 1] <= linear) ++k;
  return static_cast<std::uint8_t>(k);
}

}  // namespace

std::uint8_t srgb_byte(float linear) { return code_of(code_tables(), linear); }

void srgb_bytes(std::span<const float> linear, std::span<std::uint8_t> codes) {
  const CodeTables& tables = code_tables();
  for (std::size_t i = 0; i < linear.size(); ++i) codes[i] = code_of(tables, linear[i]);
}

}  // namespace quiver
