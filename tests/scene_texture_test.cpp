// Tests of scene/texture.h: build_texture checks checker parameters and
// in-memory images, and refuses an image texture whose file was not read.
#include <gtest/gtest.h>

#include <limits>
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

}  // namespace
}  // namespace quiver
