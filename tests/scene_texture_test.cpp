// Tests of scene/texture.h: build_texture checks checker parameters and
// in-memory images, and refuses an image texture whose file was not read.
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <stdexcept>

#include "scene/texture.h"

namespace quiver {
namespace {

namespace fs = std::filesystem;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

bool same(const Vec3<float>& a, const Vec3<float>& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

TEST(TextureBuild, RejectsBadCheckerScaleAndInMemoryImages) {
  TextureDesc desc;
  for (float scale : {0.f, -1.f, kNaN, kInf}) {
    desc.scale = scale;
    EXPECT_THROW(build_texture(desc), std::invalid_argument) << scale;
  }
  desc.scale = 3.f;
  desc.color_b = {0.f, kNaN, 0.f};
  EXPECT_THROW(build_texture(desc), std::invalid_argument);
  desc.color_b = {0.f, 0.5f, 0.f};
  const Texture good = build_texture(desc);
  EXPECT_EQ(good.scale, 3.f);
  EXPECT_TRUE(same(good.color_b, desc.color_b));

  TextureDesc image;
  image.kind = TextureDesc::Kind::image;
  image.width = 2;
  image.height = 1;
  image.rgb = {1.f, 2.f, 3.f, 4.f, 5.f};  // one float short
  EXPECT_THROW(build_texture(image), std::invalid_argument);
  image.rgb.push_back(6.f);
  const Texture built = build_texture(image);
  EXPECT_EQ(built.image.width, 2);
  EXPECT_EQ(built.image.rgb, image.rgb);
  image.rgb[4] = kInf;
  EXPECT_THROW(build_texture(image), std::invalid_argument);
  image.rgb[4] = 5.f;
  image.width = 0;
  image.rgb.clear();
  EXPECT_THROW(build_texture(image), std::invalid_argument);
  // Beyond the side bound: rejected before the size of rgb is looked at.
  image.width = int(kMaxTextureSide) + 1;
  EXPECT_THROW(build_texture(image), std::invalid_argument);
  image.width = int(kMaxTextureSide);
  image.height = int(kMaxTexturePixels / kMaxTextureSide) + 1;
  EXPECT_THROW(build_texture(image), std::invalid_argument);
}

// The error of build_texture(desc), or "" when it builds.
std::string build_error(const TextureDesc& desc) {
  try {
    build_texture(desc);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

// At the bounds (a side of 32768, 2^26 texels) an image passes the bound
// and is refused only for the floats it lacks; one texel past, for its size.
TEST(TextureBuild, InMemoryImagesAtTheBoundsPassThemAndOnePastDoesNot) {
  TextureDesc image;
  image.kind = TextureDesc::Kind::image;
  image.rgb = {1.f, 1.f, 1.f};
  const std::int64_t full_height = kMaxTexturePixels / kMaxTextureSide;
  for (const auto& [width, height] : {std::pair{kMaxTextureSide, std::int64_t{1}}, std::pair{std::int64_t{1}, kMaxTextureSide},
                                      std::pair{kMaxTextureSide, full_height}}) {
    image.width = int(width);
    image.height = int(height);
    EXPECT_NE(build_error(image).find("in-memory image needs"), std::string::npos) << width << " x " << height;
  }
  for (const auto& [width, height] :
       {std::pair{kMaxTextureSide + 1, std::int64_t{1}}, std::pair{std::int64_t{1}, kMaxTextureSide + 1},
        std::pair{kMaxTextureSide, full_height + 1}}) {
    image.width = int(width);
    image.height = int(height);
    EXPECT_NE(build_error(image).find("exceeds the limit of 32768 texels per side"), std::string::npos)
        << width << " x " << height;
  }
}

TEST(TextureBuild, AnImageFileNotYetReadIsRefused) {
  TextureDesc desc;
  desc.kind = TextureDesc::Kind::image;
  desc.path = "picture.png";
  try {
    build_texture(desc);
    ADD_FAILURE() << "no error for an unread image file";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("'picture.png' was not read"), std::string::npos) << error.what();
  }
}

TEST(TextureBuild, ImagesGetAMipPyramidOfTwoByTwoBoxesDownToOneTexel) {
  // 3 x 2 grey texels 0..5: level 1 is 2 x 1, its right texel repeating the
  // last column; level 2 is 1 x 1, the mean of level 1.
  TextureDesc desc;
  desc.kind = TextureDesc::Kind::image;
  desc.width = 3;
  desc.height = 2;
  for (float value : {0.f, 1.f, 2.f, 3.f, 4.f, 5.f}) desc.rgb.insert(desc.rgb.end(), {value, value, 2.f * value});
  const Texture texture = build_texture(desc);
  ASSERT_EQ(texture.coarser.size(), 2u);
  const TextureImage& half = texture.coarser[0];
  ASSERT_EQ(half.width, 2);
  ASSERT_EQ(half.height, 1);
  EXPECT_FLOAT_EQ(half.rgb[0], (0.f + 1.f + 3.f + 4.f) / 4.f);
  EXPECT_FLOAT_EQ(half.rgb[3], (2.f + 2.f + 5.f + 5.f) / 4.f);
  EXPECT_FLOAT_EQ(half.rgb[5], 2.f * (2.f + 2.f + 5.f + 5.f) / 4.f);
  const TextureImage& last = texture.coarser[1];
  ASSERT_EQ(last.width, 1);
  ASSERT_EQ(last.height, 1);
  EXPECT_FLOAT_EQ(last.rgb[0], (half.rgb[0] + half.rgb[3]) / 2.f);
  // Checkers have none.
  TextureDesc checks;
  EXPECT_TRUE(build_texture(checks).coarser.empty());
}

}  // namespace
}  // namespace quiver
