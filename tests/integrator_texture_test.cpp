// Tests of integrator/texture.h: checker parities, bilinear lookups and wrap
// modes against hand-computed values, and image files written with
// OpenImageIO into a temporary directory (sRGB decoding, linear floats,
// bounds checked before allocation, unreadable files).
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "integrator/texture.h"
#include "io/parse_error.h"
#include "tests/support/temporary_directory.h"

namespace quiver {
namespace {

namespace fs = std::filesystem;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

using testing::TemporaryDirectory;

// Writes pixels with OpenImageIO (format from the extension), colours as
// given even beside an alpha channel; fails the test on error.
void write_with_oiio(const fs::path& path, int width, int height, int channels, OIIO::TypeDesc type, const void* pixels,
                     const char* color_space = nullptr) {
  auto output = OIIO::ImageOutput::create(path.string());
  ASSERT_TRUE(output) << OIIO::geterror();
  OIIO::ImageSpec spec(width, height, channels, type);
  if (color_space != nullptr) spec.attribute("oiio:ColorSpace", color_space);
  spec.attribute("oiio:UnassociatedAlpha", 1);  // store colours as given, not divided by alpha
  ASSERT_TRUE(output->open(path.string(), spec)) << output->geterror();
  ASSERT_TRUE(output->write_image(type, pixels)) << output->geterror();
  ASSERT_TRUE(output->close()) << output->geterror();
}

// The sRGB EOTF as IEC 61966-2-1 defines it, for an 8-bit code.
float srgb_decoded(int code) {
  const double c = code / 255.0;
  return static_cast<float>(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
}

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

// The ParseError of reading path; its what() must start with "path: ".
std::string read_error(const fs::path& path) {
  try {
    read_texture_image(path);
  } catch (const ParseError& error) {
    EXPECT_EQ(error.line(), 0u);
    EXPECT_EQ(error.column(), 0u);
    const std::string what = error.what();
    EXPECT_EQ(what.rfind(path.string() + ": ", 0), 0u) << what;
    return what;
  }
  ADD_FAILURE() << "no ParseError for " << path;
  return {};
}

// Peak virtual memory of this process in KiB (Linux /proc), or -1.
long peak_virtual_kib() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmPeak:", 0) == 0) return std::stol(line.substr(7));
  }
  return -1;
}

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

// ---- image files ----

TEST(TextureFile, EightAndSixteenBitFilesAreSrgbDecoded) {
  TemporaryDirectory directory;
  const std::vector<std::uint8_t> bytes{0, 128, 255, 10, 20, 30, 200, 100, 50, 255, 1, 64};
  const fs::path rgb = directory.path() / "rgb.png";
  write_with_oiio(rgb, 2, 2, 3, OIIO::TypeDesc::UINT8, bytes.data());
  const TextureImage image = read_texture_image(rgb);
  ASSERT_EQ(image.width, 2);
  ASSERT_EQ(image.height, 2);
  ASSERT_EQ(image.rgb.size(), 12u);
  for (std::size_t i = 0; i < bytes.size(); ++i) EXPECT_EQ(image.rgb[i], srgb_decoded(bytes[i])) << i;
  EXPECT_EQ(image.rgb[0], 0.f);
  EXPECT_EQ(image.rgb[2], 1.f);
  EXPECT_NEAR(image.rgb[1], 0.2158605f, 1e-6f);  // 128 -> 0.21586...

  // Grey is replicated; alpha is dropped (grey + alpha, RGBA).
  const std::vector<std::uint8_t> grey_alpha{128, 7, 255, 9};
  const fs::path ga = directory.path() / "grey_alpha.png";
  write_with_oiio(ga, 2, 1, 2, OIIO::TypeDesc::UINT8, grey_alpha.data());
  const TextureImage grey = read_texture_image(ga);
  ASSERT_EQ(grey.rgb.size(), 6u);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(grey.rgb[c], srgb_decoded(128));
    EXPECT_EQ(grey.rgb[3 + c], 1.f);
  }
  const std::vector<std::uint8_t> rgba{10, 20, 30, 77};
  const fs::path with_alpha = directory.path() / "rgba.png";
  write_with_oiio(with_alpha, 1, 1, 4, OIIO::TypeDesc::UINT8, rgba.data());
  const TextureImage opaque = read_texture_image(with_alpha);
  ASSERT_EQ(opaque.rgb.size(), 3u);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(opaque.rgb[c], srgb_decoded(rgba[c]));

  // 16 bits: code 32768 decodes as 32768 / 65535.
  const std::vector<std::uint16_t> wide{0, 32768, 65535};
  const fs::path sixteen = directory.path() / "sixteen.png";
  write_with_oiio(sixteen, 1, 1, 3, OIIO::TypeDesc::UINT16, wide.data());
  const TextureImage deep = read_texture_image(sixteen);
  const double c = 32768.0 / 65535.0;
  EXPECT_EQ(deep.rgb[1], static_cast<float>(std::pow((c + 0.055) / 1.055, 2.4)));
  EXPECT_EQ(deep.rgb[2], 1.f);

  // A PNG that declares itself linear is not decoded.
  const fs::path linear = directory.path() / "linear.png";
  write_with_oiio(linear, 1, 1, 3, OIIO::TypeDesc::UINT16, wide.data(), "Linear");
  const TextureImage plain = read_texture_image(linear);
  EXPECT_EQ(plain.rgb[1], static_cast<float>(c));
}

TEST(TextureFile, FloatExrIsLinearAndExact) {
  TemporaryDirectory directory;
  const std::vector<float> values{0.1f, 3.5f, 1e-3f, 100.f, -0.25f, 0.7f};
  const fs::path path = directory.path() / "linear.exr";
  write_with_oiio(path, 2, 1, 3, OIIO::TypeDesc::FLOAT, values.data());
  const TextureImage image = read_texture_image(path);
  ASSERT_EQ(image.width, 2);
  ASSERT_EQ(image.height, 1);
  EXPECT_EQ(image.rgb, values);

  const std::vector<float> grey{0.3f, 2.f};
  const fs::path grey_path = directory.path() / "grey.exr";
  write_with_oiio(grey_path, 1, 2, 1, OIIO::TypeDesc::FLOAT, grey.data());
  const TextureImage grey_image = read_texture_image(grey_path);
  EXPECT_EQ(grey_image.rgb, (std::vector<float>{0.3f, 0.3f, 0.3f, 2.f, 2.f, 2.f}));

  const std::vector<float> bad{0.1f, 0.2f, 0.3f, 0.4f, kNaN, 0.6f};
  const fs::path nan_path = directory.path() / "nan.exr";
  write_with_oiio(nan_path, 2, 1, 3, OIIO::TypeDesc::FLOAT, bad.data());
  EXPECT_NE(read_error(nan_path).find("texel (1, 0) is not finite"), std::string::npos);
}

TEST(TextureFile, HugeClaimedSizeFailsBeforeAllocating) {
  TemporaryDirectory directory;
  const fs::path path = directory.path() / "huge.ppm";
  {
    std::ofstream file(path, std::ios::binary);
    file << "P6\n50000 50000\n255\n" << std::string(12, '\x7f');
  }
  // 50000^2 RGB floats would be 30 GB; the peak virtual size must not grow by that.
  const long before = peak_virtual_kib();
  ASSERT_GT(before, 0) << "cannot read VmPeak from /proc/self/status";
  const std::string what = read_error(path);
  EXPECT_NE(what.find("50000 x 50000 texels exceeds the limit of 32768 texels per side"), std::string::npos) << what;
  EXPECT_LT(peak_virtual_kib() - before, 1L << 20) << "peak virtual memory grew by more than 1 GiB";

  // The bounds hold through build_texture too.
  TextureDesc desc;
  desc.kind = TextureDesc::Kind::image;
  desc.path = path.string();
  EXPECT_THROW(build_texture(desc), ParseError);
}

TEST(TextureFile, MissingDirectoryAndNonImageFilesFailWithThePath) {
  TemporaryDirectory directory;
  EXPECT_NE(read_error(directory.path() / "missing.png").find("cannot open"), std::string::npos);
  EXPECT_NE(read_error(directory.path()).find("directory"), std::string::npos);
  const fs::path text = directory.path() / "notes.txt";
  std::ofstream(text) << "not an image\n";
  EXPECT_NE(read_error(text).find("not an image"), std::string::npos);
  const fs::path fake = directory.path() / "fake.png";
  std::ofstream(fake) << "not a PNG either\n";
  EXPECT_NE(read_error(fake).find("not an image"), std::string::npos);
}

}  // namespace
}  // namespace quiver
