// Tests of integrator/texture.h: checker parities, bilinear lookups and wrap
// modes against hand-computed values.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "integrator/texture.h"

namespace quiver {
namespace {

namespace fs = std::filesystem;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

TextureImage grey_image(int width, int height, const std::vector<float>& values) {
  TextureImage image{width, height, {}};
  for (float value : values) image.rgb.insert(image.rgb.end(), {value, value, value});
  return image;
}

Texture image_texture(TextureImage image, WrapMode wrap) {
  Texture texture;
  texture.kind = TextureDesc::Kind::image;
  texture.wrap = wrap;
  texture.image = std::move(image);
  return texture;
}

Texture checker(TextureDesc::Kind kind, float scale) {
  Texture texture;
  texture.kind = kind;
  texture.color_a = {1.f, 0.f, 0.f};
  texture.color_b = {0.f, 0.f, 1.f};
  texture.scale = scale;
  return texture;
}

bool same(const Vec3<float>& a, const Vec3<float>& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

// ---- checkers ----

TEST(TextureChecker, TwoDimensionalParityIncludingNegativeCoordinates) {
  const Texture texture = checker(TextureDesc::Kind::checker2d, 2.f);
  const Vec3<float> a = texture.color_a, b = texture.color_b, p{0.f, 0.f, 0.f};
  struct Case {
    float u, v;
    bool odd;
  };
  // Cells are floor(2u) + floor(2v).
  const Case cases[] = {
      {0.1f, 0.1f, false},   {0.6f, 0.1f, true},   {0.6f, 0.6f, false}, {0.5f, 0.f, true},      {-0.1f, 0.1f, true},
      {-0.1f, -0.1f, false}, {-0.6f, 0.1f, false}, {-0.5f, 0.f, true},  {-0.75f, -0.25f, true}, {0.f, -0.5f, true},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(::testing::Message() << "u=" << c.u << " v=" << c.v);
    EXPECT_TRUE(same(evaluate(texture, c.u, c.v, p), c.odd ? b : a));
  }
  // Large coordinates keep an exact parity: 2 * 8388607.5 = 16777215 is odd.
  EXPECT_TRUE(same(evaluate(texture, 8388607.5f, 0.f, p), b));
  EXPECT_TRUE(same(evaluate(texture, -8388607.5f, 0.f, p), b));
  EXPECT_TRUE(same(evaluate(texture, 1e30f, 0.f, p), a));
  // Non-finite coordinates count as 0.
  EXPECT_TRUE(same(evaluate(texture, kNaN, 0.6f, p), b));
  EXPECT_TRUE(same(evaluate(texture, kInf, -kInf, p), a));
}

TEST(TextureChecker, ThreeDimensionalParityOverTheWorldPoint) {
  const Texture texture = checker(TextureDesc::Kind::checker3d, 1.f);
  const Vec3<float> a = texture.color_a, b = texture.color_b;
  EXPECT_TRUE(same(evaluate(texture, 0.f, 0.f, {0.5f, 0.5f, 0.5f}), a));
  EXPECT_TRUE(same(evaluate(texture, 0.f, 0.f, {1.5f, 0.5f, 0.5f}), b));
  EXPECT_TRUE(same(evaluate(texture, 0.f, 0.f, {1.5f, 1.5f, 0.5f}), a));
  EXPECT_TRUE(same(evaluate(texture, 0.f, 0.f, {1.5f, 1.5f, 1.5f}), b));
  EXPECT_TRUE(same(evaluate(texture, 0.f, 0.f, {-0.5f, 0.5f, 0.5f}), b));
  EXPECT_TRUE(same(evaluate(texture, 0.f, 0.f, {-0.5f, -0.5f, -0.5f}), b));
  EXPECT_TRUE(same(evaluate(texture, 0.f, 0.f, {-1.5f, -0.5f, 0.5f}), b));
  // u and v do not matter; the scale does: 0.3 * 4 = 1.2 is in cell 1.
  EXPECT_TRUE(same(evaluate(texture, 0.7f, 0.2f, {0.5f, 0.5f, 0.5f}), a));
  Texture scaled = checker(TextureDesc::Kind::checker3d, 4.f);
  EXPECT_TRUE(same(evaluate(scaled, 0.f, 0.f, {0.3f, 0.1f, 0.1f}), b));
  EXPECT_TRUE(same(evaluate(texture, 0.f, 0.f, {kNaN, 0.5f, 0.5f}), a));
}

// ---- box-filtered checkers ----

TEST(TextureCheckerFiltered, ATinyFootprintGivesThePointSampledBits) {
  for (TextureDesc::Kind kind : {TextureDesc::Kind::checker2d, TextureDesc::Kind::checker3d}) {
    const Texture texture = checker(kind, 3.f);
    TextureFootprint tiny;
    tiny.du_dx = tiny.dv_dy = 1e-6f;
    tiny.dp_dx = {1e-6f, 0.f, 0.f};
    tiny.dp_dy = {0.f, 1e-6f, 1e-6f};
    for (int k = 0; k < 200; ++k) {
      const float u = -5.f + 0.0517f * float(k), v = 3.f - 0.0391f * float(k);
      const Vec3<float> p{u, v, 0.7f * u - v};
      SCOPED_TRACE(::testing::Message() << "u=" << u << " v=" << v);
      EXPECT_TRUE(same(evaluate_filtered(texture, u, v, p, tiny), evaluate(texture, u, v, p)));
      EXPECT_TRUE(same(evaluate_filtered(texture, u, v, p, TextureFootprint{}), evaluate(texture, u, v, p)));
    }
  }
}

TEST(TextureCheckerFiltered, AWholePeriodOrAnUnboundedFootprintGivesTheMeanColour) {
  const Texture texture = checker(TextureDesc::Kind::checker2d, 2.f);
  const Vec3<float> mean = (texture.color_a + texture.color_b) * 0.5f;
  // Two cells of u (one period of the square wave) average it to 0 whatever v does.
  TextureFootprint period;
  period.du_dx = 0.6f;
  period.du_dy = -0.4f;  // |0.6| + |-0.4| = 1 unit = 2 cells
  for (float u : {0.f, 0.13f, 0.25f, -7.3f}) {
    for (float v : {0.1f, 0.6f}) {
      const Vec3<float> c = evaluate_filtered(texture, u, v, {0.f, 0.f, 0.f}, period);
      EXPECT_NEAR(c.x, mean.x, 1e-6f);
      EXPECT_NEAR(c.z, mean.z, 1e-6f);
    }
  }
  TextureFootprint unbounded;
  unbounded.du_dx = kInf;
  unbounded.dv_dy = 1e-3f;
  EXPECT_TRUE(same(evaluate_filtered(texture, 0.1f, 0.1f, {0.f, 0.f, 0.f}, unbounded), mean));
  // NaN derivatives sample the point (never a NaN colour).
  TextureFootprint broken;
  broken.du_dx = broken.dv_dy = kNaN;
  EXPECT_TRUE(same(evaluate_filtered(texture, 0.1f, 0.1f, {0.f, 0.f, 0.f}, broken), texture.color_a));
}

TEST(TextureCheckerFiltered, HalfACellAcrossAnEdgeMixesTheTwoCellsByTheirShares) {
  // scale 1: a box of width 0.5 from u = 0.85 to 1.35 covers 0.15 of cell 0
  // (s = +1) and 0.35 of cell 1 (s = -1): mean s = -0.4, so with v in cell 0
  // the colour is 0.3 a + 0.7 b.
  const Texture texture = checker(TextureDesc::Kind::checker2d, 1.f);
  TextureFootprint f;
  f.du_dx = 0.5f;
  const Vec3<float> c = evaluate_filtered(texture, 1.1f, 0.5f, {0.f, 0.f, 0.f}, f);
  EXPECT_NEAR(c.x, 0.3f, 1e-6f);
  EXPECT_NEAR(c.z, 0.7f, 1e-6f);
  // The same box along x in 3D, y and z inside cell 0.
  const Texture solid = checker(TextureDesc::Kind::checker3d, 1.f);
  TextureFootprint g;
  g.dp_dy = {0.5f, 0.f, 0.f};
  const Vec3<float> d = evaluate_filtered(solid, 0.f, 0.f, {1.1f, 0.5f, 0.5f}, g);
  EXPECT_NEAR(d.x, 0.3f, 1e-6f);
  EXPECT_NEAR(d.z, 0.7f, 1e-6f);
}

// 4 x 4 texels alternating 0 and 1 (level 1: every texel 0.5).
Texture alternating_texels() {
  TextureDesc desc;
  desc.kind = TextureDesc::Kind::image;
  desc.width = desc.height = 4;
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 4; ++x) {
      const float value = float((x + y) % 2);
      desc.rgb.insert(desc.rgb.end(), {value, value, value});
    }
  }
  return build_texture(desc);
}

TEST(TextureImageFiltered, MipLevelsFollowTheFootprintInTexels) {
  const Texture texture = alternating_texels();
  const Vec3<float> p{0.f, 0.f, 0.f};
  const float u = 0.375f, v = 0.625f;  // a texel centre
  // Up to sqrt 3 texels: the bilinear lookup's bits.
  TextureFootprint small;
  small.du_dx = 0.25f * 1.7f;
  EXPECT_TRUE(same(evaluate_filtered(texture, u, v, p, small), evaluate(texture, u, v, p)));
  // 2 sqrt 3 texels: level 1 (every texel 0.5).
  TextureFootprint level_one;
  level_one.dv_dy = 0.25f * 2.f * std::sqrt(3.f);
  EXPECT_NEAR(evaluate_filtered(texture, u, v, p, level_one).x, 0.5f, 1e-6f);
  // sqrt 2 sqrt 3 texels: halfway between level 0 and level 1.
  TextureFootprint between;
  between.du_dx = 0.25f * std::sqrt(6.f);
  const float level0 = evaluate(texture, u, v, p).x;
  EXPECT_NEAR(evaluate_filtered(texture, u, v, p, between).x, 0.5f * (level0 + 0.5f), 1e-5f);
  // Unbounded: the coarsest level, the mean.
  TextureFootprint unbounded;
  unbounded.du_dx = kInf;
  EXPECT_FLOAT_EQ(evaluate_filtered(texture, u, v, p, unbounded).x, 0.5f);
}

// Between two levels the lookup is the linear blend of both at every
// fraction of a level, not only past the middle: a footprint of
// 2^blend sqrt 3 texels (level = log2(texels / sqrt 3) = blend) gives
// level 0 + blend (level 1 - level 0), on a 1 texel and a 0 texel whose next
// level is 0.5, along either footprint axis.
TEST(TextureImageFiltered, FractionalLevelsBlendInTheLevelsProportion) {
  const Texture texture = alternating_texels();
  const Vec3<float> p{0.f, 0.f, 0.f};
  const float v = 0.625f;
  for (float u : {0.125f, 0.375f}) {  // texel centres of value 1 and 0
    const float level0 = evaluate(texture, u, v, p).x, level1 = 0.5f;
    ASSERT_EQ(std::fabs(level0 - level1), 0.5f) << u;
    for (double blend : {0.125, 0.25, 0.375, 0.625, 0.75, 0.875}) {
      SCOPED_TRACE(::testing::Message() << "u=" << u << " blend " << blend);
      const float length = float(0.25 * std::sqrt(3.0) * std::exp2(blend));  // in u (or v) per pixel
      TextureFootprint along_x, along_y;
      along_x.du_dx = length;
      along_y.dv_dy = length;
      const double expected = level0 + (level1 - level0) * blend;
      EXPECT_NEAR(evaluate_filtered(texture, u, v, p, along_x).x, expected, 1e-5);
      EXPECT_NEAR(evaluate_filtered(texture, u, v, p, along_y).x, expected, 1e-5);
    }
  }
}

// ---- bilinear lookups and wrap modes ----

TEST(TextureImageLookup, TexelCentresGiveTexelValuesAndMidpointsTheAverage) {
  // 4 x 2, row 0 on top; distinct values per channel.
  TextureImage image{4, 2, {}};
  for (int r = 0; r < 2; ++r) {
    for (int i = 0; i < 4; ++i) image.rgb.insert(image.rgb.end(), {float(10 * r + i), float(-r - i), 0.25f * i});
  }
  const Texture texture = image_texture(image, WrapMode::clamp);
  auto texel = [&](int i, int r) {
    const float* t = &image.rgb[std::size_t(r * 4 + i) * 3];
    return Vec3<float>{t[0], t[1], t[2]};
  };
  for (int r = 0; r < 2; ++r) {
    for (int i = 0; i < 4; ++i) {
      const float u = (i + 0.5f) / 4.f, v = 1.f - (r + 0.5f) / 2.f;
      EXPECT_TRUE(same(evaluate(texture, u, v, {}), texel(i, r))) << i << ", " << r;
    }
  }
  // Between columns 1 and 2 of row 0 (u = 0.5), and between rows at column 3 (v = 0.5).
  const Vec3<float> across = evaluate(texture, 0.5f, 0.75f, {});
  EXPECT_EQ(across.x, (texel(1, 0).x + texel(2, 0).x) / 2.f);
  EXPECT_EQ(across.y, (texel(1, 0).y + texel(2, 0).y) / 2.f);
  EXPECT_EQ(across.z, (texel(1, 0).z + texel(2, 0).z) / 2.f);
  const Vec3<float> down = evaluate(texture, 0.875f, 0.5f, {});
  EXPECT_EQ(down.x, (texel(3, 0).x + texel(3, 1).x) / 2.f);
  EXPECT_EQ(down.y, (texel(3, 0).y + texel(3, 1).y) / 2.f);
  // A quarter of the way from column 0 to column 1: 3/4 * t0 + 1/4 * t1.
  const Vec3<float> quarter = evaluate(texture, 0.1875f, 0.75f, {});
  EXPECT_EQ(quarter.z, 0.0625f);

  // A width that is not a power of two: centres within a float rounding.
  const Texture odd = image_texture(grey_image(3, 1, {1.f, 7.f, 13.f}), WrapMode::repeat);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(evaluate(odd, (i + 0.5f) / 3.f, 0.5f, {}).x, 1.f + 6.f * i, 1e-5f);
}

TEST(TextureImageLookup, WrapModesAgainstHandComputedTaps) {
  // One row 10 20 30 40; u = -0.25 is texel coordinate -1.5 (taps -2 and -1
  // at weight 1/2), u = 1.25 is 4.5 (taps 4 and 5); u = -0.875 and 2.125
  // land exactly on the texel coordinates -4 and 8.
  const TextureImage row = grey_image(4, 1, {10.f, 20.f, 30.f, 40.f});
  struct Case {
    WrapMode wrap;
    float u, expected;
  };
  const Case cases[] = {
      {WrapMode::repeat, -0.25f, 35.f}, {WrapMode::repeat, 1.25f, 15.f},   {WrapMode::repeat, -0.875f, 10.f},
      {WrapMode::repeat, 2.125f, 10.f}, {WrapMode::clamp, -0.25f, 10.f},   {WrapMode::clamp, 1.25f, 40.f},
      {WrapMode::clamp, -0.875f, 10.f}, {WrapMode::clamp, 2.125f, 40.f},   {WrapMode::mirror, -0.25f, 15.f},
      {WrapMode::mirror, 1.25f, 35.f},  {WrapMode::mirror, -0.875f, 40.f}, {WrapMode::mirror, 2.125f, 10.f},
      {WrapMode::repeat, 0.f, 25.f},    {WrapMode::clamp, 0.f, 10.f},      {WrapMode::mirror, 0.f, 10.f},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(::testing::Message() << "wrap " << int(c.wrap) << " u=" << c.u);
    const Vec3<float> color = evaluate(image_texture(row, c.wrap), c.u, 0.3f, {});
    EXPECT_EQ(color.x, c.expected);
    EXPECT_EQ(color.z, c.expected);
  }
  // One column, top 1 and bottom 5: v = 1.25 is row coordinate -1, v = -0.25 is 2.
  const TextureImage column = grey_image(1, 2, {1.f, 5.f});
  EXPECT_EQ(evaluate(image_texture(column, WrapMode::repeat), 0.5f, 1.25f, {}).x, 5.f);
  EXPECT_EQ(evaluate(image_texture(column, WrapMode::clamp), 0.5f, 1.25f, {}).x, 1.f);
  EXPECT_EQ(evaluate(image_texture(column, WrapMode::mirror), 0.5f, 1.25f, {}).x, 1.f);
  EXPECT_EQ(evaluate(image_texture(column, WrapMode::repeat), 0.5f, -0.25f, {}).x, 1.f);
  EXPECT_EQ(evaluate(image_texture(column, WrapMode::clamp), 0.5f, -0.25f, {}).x, 5.f);
  EXPECT_EQ(evaluate(image_texture(column, WrapMode::mirror), 0.5f, -0.25f, {}).x, 5.f);
}

TEST(TextureImageLookup, NonFiniteAndHugeCoordinatesGiveFiniteColours) {
  const TextureImage row = grey_image(4, 1, {10.f, 20.f, 30.f, 40.f});
  for (WrapMode wrap : {WrapMode::repeat, WrapMode::clamp, WrapMode::mirror}) {
    const Texture texture = image_texture(row, wrap);
    const Vec3<float> at_origin = evaluate(texture, 0.f, 0.f, {});
    EXPECT_TRUE(same(evaluate(texture, kNaN, kNaN, {}), at_origin));
    EXPECT_TRUE(same(evaluate(texture, kInf, -kInf, {}), at_origin));
    for (float u : {3e38f, -3e38f, 1e20f, -16777217.f, 123456.789f}) {
      const float value = evaluate(texture, u, u, {}).x;
      EXPECT_TRUE(value >= 10.f && value <= 40.f) << "u=" << u << " gives " << value;
    }
  }
}

}  // namespace
}  // namespace quiver
