// Textures as the renderer samples them: checker parameters, or an image's
// linear RGB texels in memory (io/texture_image.h reads image files into a
// TextureDesc before the scene is built). Conventions: an image's row 0 is
// the top (v = 1) and its last row v = 0; texel (i, row r) has its centre
// at u = (i + 0.5) / width, v = 1 - (r + 0.5) / height.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene_desc.h"

namespace quiver {

// Largest image side and texel count accepted, checked before any texel is
// read or allocated (64 Mi texels are 768 MiB of RGB floats).
inline constexpr std::int64_t kMaxTextureSide = 32'768;
inline constexpr std::int64_t kMaxTexturePixels = std::int64_t{1} << 26;

// "the limit of N texels per side and M texels in total", for messages.
std::string texture_size_limit_text();

// Linear RGB texels, 3 floats each, row-major with row 0 at the top (v = 1).
struct TextureImage {
  int width = 0, height = 0;
  std::vector<float> rgb;
};

// A texture ready to evaluate (integrator/texture.h).
struct Texture {
  TextureDesc::Kind kind = TextureDesc::Kind::checker2d;
  Vec3<float> color_a{1.f, 1.f, 1.f}, color_b{0.f, 0.f, 0.f};
  float scale = 1.f;
  WrapMode wrap = WrapMode::repeat;
  TextureImage image;  // image textures only
  // Image textures: the MIP pyramid's levels below `image`, each a 2 x 2
  // box of the one above (half the size, odd sides rounded up, the last
  // row and column repeated), down to 1 x 1.
  std::vector<TextureImage> coarser;
};

// Checks desc and takes its in-memory image (desc.width x desc.height
// desc.rgb). Throws std::invalid_argument for an image texture without
// pixels (a file texture not yet read), bad in-memory data, a checker scale
// that is not finite and positive, or non-finite checker colours.
Texture build_texture(const TextureDesc& desc);

}  // namespace quiver
