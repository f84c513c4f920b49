// Textures: 2D and 3D checkerboards and bilinearly filtered images.
// Conventions: colours are linear RGB; an image's row 0 is the top (v = 1)
// and its last row v = 0; texel (i, row r) has its centre at
// u = (i + 0.5) / width, v = 1 - (r + 0.5) / height. Wrap modes act on the
// integer texel indices of the four bilinear taps. Checker parities are
// computed in double from floor(coordinate * scale), so they are exact for
// every finite float. Non-finite u, v or world coordinates count as 0, so
// evaluate never returns NaN.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "io/scene_desc.h"
#include "simd/vec3.h"

namespace quiver {

// Largest image side and texel count accepted, checked before any texel is
// read or allocated (64 Mi texels are 768 MiB of RGB floats).
inline constexpr std::int64_t kMaxTextureSide = 32'768;
inline constexpr std::int64_t kMaxTexturePixels = std::int64_t{1} << 26;

// Linear RGB texels, 3 floats each, row-major with row 0 at the top (v = 1).
struct TextureImage {
  int width = 0, height = 0;
  std::vector<float> rgb;
};

// Reads an image file through OpenImageIO. One channel is grey (replicated),
// two are grey + alpha, three or more are RGB (+ alpha); alpha is dropped.
// Integer formats are sRGB-decoded (exact EOTF) unless the file's
// "oiio:ColorSpace" names a linear space; float formats are linear. Throws
// ParseError ("file: message") for a missing, unreadable or non-image file,
// sizes beyond the bounds above, or non-finite texels.
TextureImage read_texture_image(const std::filesystem::path& path);

// A texture ready to evaluate.
struct Texture {
  TextureDesc::Kind kind = TextureDesc::Kind::checker2d;
  Vec3<float> color_a{1.f, 1.f, 1.f}, color_b{0.f, 0.f, 0.f};
  float scale = 1.f;
  WrapMode wrap = WrapMode::repeat;
  TextureImage image;  // image textures only
};

// Checks desc and loads the image (desc.path when non-empty, else the
// in-memory desc.width x desc.height desc.rgb). Throws ParseError for a bad
// file and std::invalid_argument for bad in-memory data, a checker scale
// that is not finite and positive, or non-finite checker colours.
Texture build_texture(const TextureDesc& desc);

// The texture's colour at surface coordinates (u, v) and world point p.
// checker2d: color_a where floor(u*scale) + floor(v*scale) is even, else
// color_b; checker3d: the same over floor(p.x*scale) + floor(p.y*scale) +
// floor(p.z*scale); image: bilinear over the four texels around (u, v).
Vec3<float> evaluate(const Texture& texture, float u, float v, const Vec3<float>& world_point);

}  // namespace quiver
