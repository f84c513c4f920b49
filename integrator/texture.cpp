// Texture loading (OpenImageIO) and evaluation: checker parities and
// bilinear image lookups computed in double over the float texels.
#include "integrator/texture.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>

#include "io/parse_error.h"

namespace quiver {

namespace {

namespace fs = std::filesystem;

constexpr std::size_t kUint16Levels = 65'536;

[[noreturn]] void fail(const fs::path& path, std::string_view message) {
  throw ParseError::whole_file(path.string(), message);
}

std::string size_limit_text() {
  return "the limit of " + std::to_string(kMaxTextureSide) + " texels per side and " +
         std::to_string(kMaxTexturePixels) + " texels in total";
}

// The sRGB EOTF (IEC 61966-2-1), encoded value in [0, 1] to linear.
double srgb_to_linear(double encoded) {
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

// Linear value of each 16-bit code of an sRGB-encoded channel. An 8-bit code
// c widens exactly to c * 257, and c * 257 / 65535 == c / 255.
const std::vector<float>& srgb_uint16_table() {
  static const std::vector<float> table = [] {
    std::vector<float> values(kUint16Levels);
    for (std::size_t code = 0; code < kUint16Levels; ++code) {
      values[code] = static_cast<float>(srgb_to_linear(double(code) / 65535.0));
    }
    return values;
  }();
  return table;
}

// True when the file's colour space metadata names a linear encoding.
bool names_linear_space(std::string color_space) {
  for (char& c : color_space) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return color_space.find("linear") != std::string::npos || color_space.rfind("lin_", 0) == 0 ||
         color_space == "acescg" || color_space == "aces2065-1";
}

// Copies the first channel of each texel into the other two (grey images).
void replicate_grey(std::vector<float>& rgb) {
  for (std::size_t i = 0; i < rgb.size(); i += 3) rgb[i + 1] = rgb[i + 2] = rgb[i];
}

void check_finite_texels(const fs::path& path, const TextureImage& image) {
  for (std::size_t i = 0; i < image.rgb.size(); ++i) {
    if (!std::isfinite(image.rgb[i])) {
      const std::size_t texel = i / 3;
      const std::size_t width = static_cast<std::size_t>(image.width);
      fail(path, "texel (" + std::to_string(texel % width) + ", " + std::to_string(texel / width) +
                     ") is not finite (NaN or infinity)");
    }
  }
}

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

bool finite(const Vec3<float>& c) { return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z); }

// The in-memory image of a TextureDesc, checked.
TextureImage image_from_memory(const TextureDesc& desc) {
  const std::int64_t w = desc.width, h = desc.height;
  if (w < 1 || h < 1 || w > kMaxTextureSide || h > kMaxTextureSide || w * h > kMaxTexturePixels) {
    throw std::invalid_argument("texture: in-memory image of " + std::to_string(w) + " x " + std::to_string(h) +
                                " texels is empty or exceeds " + size_limit_text());
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

}  // namespace

TextureImage read_texture_image(const fs::path& path) {
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (!fs::exists(status)) fail(path, "cannot open: no such file");
  if (fs::is_directory(status)) fail(path, "cannot open: it is a directory");

  // Colours as stored: OpenImageIO would otherwise premultiply them by alpha.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto input = OIIO::ImageInput::open(path.string(), &config);
  if (!input) fail(path, "not an image OpenImageIO can read (" + OIIO::geterror() + ")");
  const OIIO::ImageSpec& spec = input->spec();

  // Bounds first: nothing is sized from the header before this.
  const std::int64_t w = spec.width, h = spec.height;
  if (w < 1 || h < 1 || spec.nchannels < 1) fail(path, "the image is empty");
  if (spec.depth != 1) fail(path, "volume images (depth " + std::to_string(spec.depth) + ") are not textures");
  if (w > kMaxTextureSide || h > kMaxTextureSide || w * h > kMaxTexturePixels) {
    fail(path, std::to_string(w) + " x " + std::to_string(h) + " texels exceeds " + size_limit_text());
  }

  TextureImage image;
  image.width = spec.width;
  image.height = spec.height;
  const std::size_t texels = std::size_t(w * h);
  const int channels = spec.nchannels >= 3 ? 3 : 1;  // grey (+ alpha) or RGB (+ alpha)
  image.rgb.resize(texels * 3);

  if (spec.format.is_floating_point()) {
    // Linear floats straight into the RGB array; grey lands in the first slot.
    if (!input->read_image(0, 0, 0, channels, OIIO::TypeFloat, image.rgb.data(), 3 * sizeof(float))) {
      fail(path, "cannot read the pixels (" + input->geterror() + ")");
    }
    if (channels == 1) replicate_grey(image.rgb);
    check_finite_texels(path, image);
  } else {
    // Integer codes widened to 16 bits (exact), then decoded per code.
    std::vector<std::uint16_t> codes(texels * std::size_t(channels));
    if (!input->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT16, codes.data())) {
      fail(path, "cannot read the pixels (" + input->geterror() + ")");
    }
    const bool linear = names_linear_space(spec.get_string_attribute("oiio:ColorSpace"));
    const std::vector<float>& srgb = srgb_uint16_table();
    for (std::size_t t = 0; t < texels; ++t) {
      for (std::size_t c = 0; c < 3; ++c) {
        const std::uint16_t code = codes[t * std::size_t(channels) + (channels == 1 ? 0 : c)];
        image.rgb[t * 3 + c] = linear ? static_cast<float>(double(code) / 65535.0) : srgb[code];
      }
    }
  }
  input->close();
  return image;
}

Texture build_texture(const TextureDesc& desc) {
  Texture texture;
  texture.kind = desc.kind;
  texture.color_a = desc.color_a;
  texture.color_b = desc.color_b;
  texture.scale = desc.scale;
  texture.wrap = desc.wrap;
  if (desc.kind == TextureDesc::Kind::image) {
    texture.image = desc.path.empty() ? image_from_memory(desc) : read_texture_image(desc.path);
    return texture;
  }
  if (!std::isfinite(desc.scale) || desc.scale <= 0.f) {
    throw std::invalid_argument("texture: checker scale must be finite and positive, is " + std::to_string(desc.scale));
  }
  if (!finite(desc.color_a) || !finite(desc.color_b)) {
    throw std::invalid_argument("texture: checker colours must be finite");
  }
  return texture;
}

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
