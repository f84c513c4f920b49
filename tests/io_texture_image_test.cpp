// Tests of io/texture_image.h: image files written with OpenImageIO into a
// temporary directory (sRGB decoding, linear floats, bounds checked before
// allocation, unreadable files), and a scene's textures read from files.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "io/parse_error.h"
#include "io/texture_image.h"
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

  // The bounds hold when a scene's textures are read too.
  SceneDesc scene;
  scene.textures.emplace_back();
  scene.textures.back().kind = TextureDesc::Kind::image;
  scene.textures.back().path = path.string();
  EXPECT_THROW(read_texture_images(scene), ParseError);
  EXPECT_TRUE(scene.textures.back().rgb.empty());
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

TEST(TextureFile, ASceneTexturesFilesAreReadIntoTheirDescriptions) {
  TemporaryDirectory directory;
  const fs::path path = directory.path() / "two.exr";
  const float pixels[6] = {0.25f, 0.5f, 0.75f, 1.f, 2.f, 3.f};
  write_with_oiio(path, 2, 1, 3, OIIO::TypeDesc::FLOAT, pixels);
  SceneDesc scene;
  scene.textures.resize(2);
  scene.textures[0].kind = TextureDesc::Kind::image;
  scene.textures[0].path = path.string();
  scene.textures[1].kind = TextureDesc::Kind::checker2d;
  read_texture_images(scene);
  EXPECT_EQ(scene.textures[0].width, 2);
  EXPECT_EQ(scene.textures[0].height, 1);
  EXPECT_EQ(scene.textures[0].rgb, std::vector<float>(pixels, pixels + 6));
  EXPECT_TRUE(scene.textures[1].rgb.empty());
}

}  // namespace
}  // namespace quiver
