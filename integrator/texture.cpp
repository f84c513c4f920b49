// Texture evaluation: checker parities and bilinear image lookups computed
// in double over the float texels; point sampling is the filter at a zero
// footprint.
#include "integrator/texture.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>

namespace quiver {

namespace {

float finite_or_zero(float x) { return std::isfinite(x) ? x : 0.f; }

// Integral of the square wave (-1)^floor(t) from 0 to x: a triangle wave
// of period 2 rising from 0 to 1 on [0, 1].
double integrated_square_wave(double x) {
  const double r = x - 2.0 * std::floor(0.5 * x);
  return r < 1.0 ? r : 2.0 - r;
}

// The square wave (-1)^floor(c) averaged over [c - w/2, c + w/2], all in
// cells; exactly +-1 below kPointFootprint (the parity of floor(c), exact
// in double: c is a product of two floats), 0 for an unbounded width.
double box_filtered_square_wave(double c, double w) {
  if (!(w > kPointFootprint)) return std::fmod(std::floor(c), 2.0) != 0.0 ? -1.0 : 1.0;
  if (!(w < 1e9)) return 0.0;
  return (integrated_square_wave(c + 0.5 * w) - integrated_square_wave(c - 0.5 * w)) / w;
}

// a where the product of the square waves is +1, b where -1, linear between.
Vec3<float> checker_mix(const Vec3<float>& a, const Vec3<float>& b, double product) {
  const double share_a = 0.5 * (1.0 + product), share_b = 0.5 * (1.0 - product);
  return {float(share_a * a.x + share_b * b.x), float(share_a * a.y + share_b * b.y),
          float(share_a * a.z + share_b * b.z)};
}

// The box width of one axis in cells: |d/dx| + |d/dy| times the scale.
double footprint_cells(float d_dx, float d_dy, float scale) {
  return (std::fabs(double(d_dx)) + std::fabs(double(d_dy))) * double(scale);
}

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

// Trilinear MIP mapping (Williams 1983), between two levels linearly. The
// level's blur matches a box over the footprint's longer side, w texels: a
// level-l texel is a box of 2^l texels, bilinear adds a tent of half-width
// 2^l, together a variance of 4^l / 4 against the box's w^2 / 12, so
// l = log2(w / sqrt 3). Up to sqrt 3 texels, the bilinear lookup of evaluate.
Vec3<float> mip_mapped(const Texture& texture, float u, float v, const TextureFootprint& f) {
  const double w = texture.image.width, h = texture.image.height;
  const double along_x = std::hypot(double(f.du_dx) * w, double(f.dv_dx) * h);
  const double along_y = std::hypot(double(f.du_dy) * w, double(f.dv_dy) * h);
  const double texels = std::max(along_x, along_y) / std::numbers::sqrt3;
  if (!(texels > 1.0)) return bilinear(texture.image, texture.wrap, u, v);
  const int coarsest = int(texture.coarser.size());
  const double level = std::min(std::log2(texels), double(coarsest));  // inf: the coarsest
  const int finer = std::min(int(level), coarsest);
  const double blend = level - finer;
  auto at = [&](int l) { return bilinear(l == 0 ? texture.image : texture.coarser[std::size_t(l - 1)], texture.wrap, u, v); };
  const Vec3<float> a = at(finer);
  if (finer == coarsest || blend == 0.0) return a;
  const Vec3<float> b = at(finer + 1);
  return {float(a.x + (double(b.x) - a.x) * blend), float(a.y + (double(b.y) - a.y) * blend),
          float(a.z + (double(b.z) - a.z) * blend)};
}

}  // namespace

Vec3<float> evaluate_filtered(const Texture& texture, float u, float v, const Vec3<float>& world_point,
                              const TextureFootprint& f) {
  const double scale = texture.scale;
  switch (texture.kind) {
    case TextureDesc::Kind::checker2d: {
      const double product =
          box_filtered_square_wave(double(finite_or_zero(u)) * scale, footprint_cells(f.du_dx, f.du_dy, texture.scale)) *
          box_filtered_square_wave(double(finite_or_zero(v)) * scale, footprint_cells(f.dv_dx, f.dv_dy, texture.scale));
      return checker_mix(texture.color_a, texture.color_b, product);
    }
    case TextureDesc::Kind::checker3d: {
      double product = 1.0;
      for (int axis = 0; axis < 3; ++axis) {
        product *= box_filtered_square_wave(double(finite_or_zero(world_point[axis])) * scale,
                                            footprint_cells(f.dp_dx[axis], f.dp_dy[axis], texture.scale));
      }
      return checker_mix(texture.color_a, texture.color_b, product);
    }
    case TextureDesc::Kind::image:
    default:
      return mip_mapped(texture, u, v, f);
  }
}

Vec3<float> evaluate(const Texture& texture, float u, float v, const Vec3<float>& world_point) {
  // A zero footprint: checker parities and the bilinear lookup exactly.
  return evaluate_filtered(texture, u, v, world_point, TextureFootprint{});
}

}  // namespace quiver
