#include "scene/anti_aliasing.h"

#include <charconv>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace quiver {

namespace {

const char* const kExpected =
    "expected none, grid:N, jitter:N, adaptive:THRESHOLD:DEPTH, corners or refine:THRESHOLD:N[:jitter|grid]";

std::vector<std::string_view> split(std::string_view text) {
  std::vector<std::string_view> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t colon = text.find(':', start);
    parts.push_back(text.substr(start, colon - start));
    if (colon == std::string_view::npos) return parts;
    start = colon + 1;
  }
}

int parse_int(std::string_view text, int lo, int hi, const char* what) {
  int value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || value < lo || value > hi) {
    throw std::invalid_argument("anti-aliasing " + std::string(what) + ": expected an integer in [" +
                                std::to_string(lo) + ", " + std::to_string(hi) + "], found '" + std::string(text) + "'");
  }
  return value;
}

float parse_threshold(std::string_view text) {
  float value = 0.f;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value) || value < 0.f) {
    throw std::invalid_argument("anti-aliasing threshold: expected a finite number >= 0, found '" +
                                std::string(text) + "'");
  }
  return value;
}

constexpr std::string_view kStrataNames[] = {"jitter", "grid"};

AntiAliasing::Strata parse_strata(std::string_view text) {
  for (std::size_t k = 0; k < std::size(kStrataNames); ++k) {
    if (text == kStrataNames[k]) return static_cast<AntiAliasing::Strata>(k);
  }
  throw std::invalid_argument("anti-aliasing strata: expected jitter or grid, found '" + std::string(text) + "'");
}

}  // namespace

AntiAliasing parse_anti_aliasing(std::string_view text) {
  const std::vector<std::string_view> parts = split(text);
  AntiAliasing aa;
  const std::string_view mode = parts[0];
  if ((mode == "none" || mode == "corners") && parts.size() == 1) {
    aa.mode = mode == "none" ? AntiAliasing::Mode::none : AntiAliasing::Mode::corners;
    return aa;
  }
  if ((mode == "grid" || mode == "jitter") && parts.size() == 2) {
    aa.mode = mode == "grid" ? AntiAliasing::Mode::grid : AntiAliasing::Mode::jitter;
    aa.n = parse_int(parts[1], 1, AntiAliasing::kMaxRaysPerSide, "rays per side");
    return aa;
  }
  if (mode == "adaptive" && parts.size() == 3) {
    aa.mode = AntiAliasing::Mode::adaptive;
    aa.threshold = parse_threshold(parts[1]);
    aa.depth = parse_int(parts[2], 0, AntiAliasing::kMaxDepth, "depth");
    return aa;
  }
  if (mode == "refine" && (parts.size() == 3 || parts.size() == 4)) {
    aa.mode = AntiAliasing::Mode::refine;
    aa.threshold = parse_threshold(parts[1]);
    aa.n = parse_int(parts[2], 2, AntiAliasing::kMaxRefineSide, "rays per side");
    if ((aa.n & (aa.n - 1)) != 0) {
      throw std::invalid_argument("anti-aliasing rays per side: expected a power of two (2, 4, 8 or 16), found '" +
                                  std::string(parts[2]) + "'");
    }
    if (parts.size() == 4) aa.strata = parse_strata(parts[3]);
    return aa;
  }
  throw std::invalid_argument(std::string("anti-aliasing: ") + kExpected + ", found '" + std::string(text) + "'");
}

std::string to_string(const AntiAliasing& aa) {
  switch (aa.mode) {
    case AntiAliasing::Mode::none: return "none";
    case AntiAliasing::Mode::corners: return "corners";
    case AntiAliasing::Mode::grid: return "grid:" + std::to_string(aa.n);
    case AntiAliasing::Mode::jitter: return "jitter:" + std::to_string(aa.n);
    case AntiAliasing::Mode::adaptive:
    case AntiAliasing::Mode::refine: break;
  }
  char threshold[32];
  const auto end = std::to_chars(threshold, threshold + sizeof threshold, aa.threshold).ptr;
  if (aa.mode == AntiAliasing::Mode::refine) {
    std::string text = "refine:";
    text.append(threshold, end).append(":").append(std::to_string(aa.n));
    if (aa.strata != AntiAliasing::Strata::jitter) {
      text.append(":").append(kStrataNames[static_cast<std::size_t>(aa.strata)]);
    }
    return text;
  }
  return "adaptive:" + std::string(threshold, end) + ":" + std::to_string(aa.depth);
}

}  // namespace quiver
