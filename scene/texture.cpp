#include "scene/texture.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace quiver {

namespace {

// The in-memory image of a TextureDesc, checked.
TextureImage image_from_memory(const TextureDesc& desc) {
  if (desc.rgb.empty() && !desc.path.empty()) {
    throw std::invalid_argument("texture: the image '" + desc.path + "' was not read");
  }
  if (desc.rgb.empty() && !desc.encoded.empty()) throw std::invalid_argument("texture: an embedded image was not decoded");
  const std::int64_t w = desc.width, h = desc.height;
  if (w < 1 || h < 1 || w > kMaxTextureSide || h > kMaxTextureSide || w * h > kMaxTexturePixels) {
    throw std::invalid_argument("texture: in-memory image of " + std::to_string(w) + " x " + std::to_string(h) +
                                " texels is empty or exceeds " + texture_size_limit_text());
  }
  if (desc.rgb.size() != std::size_t(w * h * 3)) {
    throw std::invalid_argument("texture: in-memory image needs " + std::to_string(w * h * 3) +
                                " floats (3 per texel), has " + std::to_string(desc.rgb.size()));
  }
  for (float value : desc.rgb) {
    if (!std::isfinite(value)) throw std::invalid_argument("texture: in-memory image has a non-finite texel");
  }
  return {desc.width, desc.height, desc.rgb};
}

// The next MIP level: each texel the mean of a 2 x 2 block of `finer`.
TextureImage half_size(const TextureImage& finer) {
  TextureImage coarser{(finer.width + 1) / 2, (finer.height + 1) / 2, {}};
  coarser.rgb.resize(std::size_t(coarser.width) * std::size_t(coarser.height) * 3);
  for (int y = 0; y < coarser.height; ++y) {
    for (int x = 0; x < coarser.width; ++x) {
      for (int c = 0; c < 3; ++c) {
        double sum = 0.0;
        for (int dy = 0; dy < 2; ++dy) {
          for (int dx = 0; dx < 2; ++dx) {
            const std::size_t fx = std::size_t(std::min(2 * x + dx, finer.width - 1));
            const std::size_t fy = std::size_t(std::min(2 * y + dy, finer.height - 1));
            sum += finer.rgb[(fy * std::size_t(finer.width) + fx) * 3 + std::size_t(c)];
          }
        }
        coarser.rgb[(std::size_t(y) * std::size_t(coarser.width) + std::size_t(x)) * 3 + std::size_t(c)] =
            float(0.25 * sum);
      }
    }
  }
  return coarser;
}

}  // namespace

std::string texture_size_limit_text() {
  return "the limit of " + std::to_string(kMaxTextureSide) + " texels per side and " +
         std::to_string(kMaxTexturePixels) + " texels in total";
}

Texture build_texture(const TextureDesc& desc) {
  Texture texture;
  texture.kind = desc.kind;
  texture.color_a = desc.color_a;
  texture.color_b = desc.color_b;
  texture.scale = desc.scale;
  texture.wrap = desc.wrap;
  if (desc.kind == TextureDesc::Kind::image) {
    texture.image = image_from_memory(desc);
    for (const TextureImage* level = &texture.image; level->width > 1 || level->height > 1;
         level = &texture.coarser.back()) {
      texture.coarser.push_back(half_size(*level));
    }
    return texture;
  }
  if (!std::isfinite(desc.scale) || desc.scale <= 0.f) {
    throw std::invalid_argument("texture: checker scale must be finite and positive, is " + std::to_string(desc.scale));
  }
  if (!all_finite(desc.color_a) || !all_finite(desc.color_b)) {
    throw std::invalid_argument("texture: checker colours must be finite");
  }
  return texture;
}

}  // namespace quiver
