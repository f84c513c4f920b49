// Texture evaluation: checker parities and bilinear image lookups computed
// in double over the float texels.
#include "integrator/texture.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace quiver {

namespace {

// Exact parity of floor(coordinate * scale): the product of two floats is
// exact in double, and fmod is exact.
bool odd_cell(float coordinate, float scale) {
  const double cell = std::floor(double(coordinate) * double(scale));
  return std::fmod(cell, 2.0) != 0.0;
}

float finite_or_zero(float x) { return std::isfinite(x) ? x : 0.f; }

// Texel index for an integer-valued cell (any magnitude) under the wrap mode.
std::size_t wrapped_index(double cell, int size, WrapMode wrap) {
  const double n = size;
  switch (wrap) {
    case WrapMode::clamp:
      return cell <= 0.0 ? 0 : (cell >= n - 1.0 ? std::size_t(size - 1) : std::size_t(cell));
    case WrapMode::mirror: {
      double r = std::fmod(cell, 2.0 * n);
      if (r < 0.0) r += 2.0 * n;
      return std::size_t(r < n ? r : 2.0 * n - 1.0 - r);
    }
    case WrapMode::repeat:
    default: {
      double r = std::fmod(cell, n);
      if (r < 0.0) r += n;
      return std::size_t(r);
    }
  }
}

Vec3<float> bilinear(const TextureImage& image, WrapMode wrap, float u, float v) {
  const std::size_t texels = std::size_t(std::max(image.width, 0)) * std::size_t(std::max(image.height, 0));
  if (texels == 0 || image.rgb.size() != texels * 3) return {0.f, 0.f, 0.f};  // not from build_texture
  // Continuous texel coordinates: texel centres sit on integers; v = 1 is row 0.
  const double x = double(finite_or_zero(u)) * image.width - 0.5;
  const double y = (1.0 - double(finite_or_zero(v))) * image.height - 0.5;
  const double x0 = std::floor(x), y0 = std::floor(y);
  const double fx = x - x0, fy = y - y0;
  const std::size_t columns[2] = {wrapped_index(x0, image.width, wrap), wrapped_index(x0 + 1.0, image.width, wrap)};
  const std::size_t rows[2] = {wrapped_index(y0, image.height, wrap), wrapped_index(y0 + 1.0, image.height, wrap)};
  const std::size_t stride = static_cast<std::size_t>(image.width);
  Vec3<float> result;
  for (int c = 0; c < 3; ++c) {
    auto texel = [&](int row, int column) {
      return double(image.rgb[(rows[row] * stride + columns[column]) * 3 + std::size_t(c)]);
    };
    const double upper = texel(0, 0) * (1.0 - fx) + texel(0, 1) * fx;
    const double lower = texel(1, 0) * (1.0 - fx) + texel(1, 1) * fx;
    result[c] = static_cast<float>(upper * (1.0 - fy) + lower * fy);
  }
  return result;
}

}  // namespace

Vec3<float> evaluate(const Texture& texture, float u, float v, const Vec3<float>& world_point) {
  switch (texture.kind) {
    case TextureDesc::Kind::checker2d: {
      const bool odd = odd_cell(finite_or_zero(u), texture.scale) != odd_cell(finite_or_zero(v), texture.scale);
      return odd ? texture.color_b : texture.color_a;
    }
    case TextureDesc::Kind::checker3d: {
      bool odd = false;
      for (int axis = 0; axis < 3; ++axis) odd = odd != odd_cell(finite_or_zero(world_point[axis]), texture.scale);
      return odd ? texture.color_b : texture.color_a;
    }
    case TextureDesc::Kind::image:
    default:
      return bilinear(texture.image, texture.wrap, u, v);
  }
}

}  // namespace quiver
