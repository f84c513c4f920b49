// The rendered image and its optional AOVs, row-major with row 0 at the top.
// Colours are linear RGB; writers encode them (io/image_output.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/primitive_kind.h"

namespace quiver {

struct Framebuffer {
  int width = 0, height = 0;
  std::vector<float> rgb;  // 3 per pixel

  // AOVs, each empty unless requested; through the pixel centre.
  std::vector<float> depth;        // distance along the unit primary ray; +inf on a miss
  std::vector<float> normal;       // 3 per pixel: unit shading normal facing the ray; 0 on a miss
  std::vector<std::int32_t> kind;  // PrimitiveKind, or kNoKind
  std::vector<std::int32_t> id;    // primitive index within its kind's input list, or -1

  Framebuffer() = default;
  Framebuffer(int w, int h) : width(w), height(h), rgb(std::size_t(w) * std::size_t(h) * 3, 0.f) {}
  std::size_t pixel_count() const { return std::size_t(width) * std::size_t(height); }
};

}  // namespace quiver
