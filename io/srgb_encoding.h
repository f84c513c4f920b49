// 8-bit sRGB codes of linear values: the sRGB OETF (IEC 61966-2-1) of the
// value clamped to [0, 1], rounded to the nearest of 256 codes; NaN is 0.
// srgb_byte_formula evaluates it in double (the reference). srgb_byte looks
// the code up among the 255 thresholds where it steps up, each found once
// by bisecting the floats of [0, 1] against the formula (the code never
// falls as the value rises, so both agree on every float), starting from
// the code of the value's bucket of floats (its top 16 bits).
#pragma once

#include <cstdint>
#include <span>

namespace quiver {

std::uint8_t srgb_byte_formula(float linear);
std::uint8_t srgb_byte(float linear);
// codes[i] = srgb_byte(linear[i]); codes at least as long as linear.
void srgb_bytes(std::span<const float> linear, std::span<std::uint8_t> codes);

}  // namespace quiver
