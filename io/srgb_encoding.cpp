#include "io/srgb_encoding.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>

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

std::uint8_t srgb_byte(float linear) {
  static const std::array<float, 256> thresholds = code_thresholds();
  // The largest k with thresholds[k] <= linear, in 8 halving steps (NaN
  // compares false throughout: code 0).
  std::size_t k = 0;
  for (std::size_t step = 128; step > 0; step /= 2) {
    k += thresholds[k + step] <= linear ? step : 0;
  }
  return static_cast<std::uint8_t>(k);
}

}  // namespace quiver
