// Tests of io/texture_image.h: image files written with OpenImageIO into a
// temporary directory (sRGB decoding, linear floats, bounds checked before
// allocation, unreadable files), and a scene's textures read from files.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "io/image_signature.h"
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

// A side of exactly kMaxTextureSide texels is read, one more is refused, on either axis.
TEST(TextureFile, SidesUpToTheBoundAreRead) {
  TemporaryDirectory directory;
  const auto write_ppm = [&](std::int64_t width, std::int64_t height) {
    const fs::path path = directory.path() / ("strip_" + std::to_string(width) + "x" + std::to_string(height) + ".ppm");
    std::ofstream file(path, std::ios::binary);
    file << "P6\n" << width << " " << height << "\n255\n" << std::string(std::size_t(3 * width * height), '\x40');
    return path;
  };
  const TextureImage wide = read_texture_image(write_ppm(kMaxTextureSide, 1));
  EXPECT_EQ(wide.width, kMaxTextureSide);
  const TextureImage tall = read_texture_image(write_ppm(1, kMaxTextureSide));
  EXPECT_EQ(tall.height, kMaxTextureSide);
  for (const auto& [width, height] :
       {std::pair{kMaxTextureSide + 1, std::int64_t{1}}, std::pair{std::int64_t{1}, kMaxTextureSide + 1}}) {
    const std::string what = read_error(write_ppm(width, height));
    EXPECT_NE(what.find("exceeds the limit of 32768 texels per side"), std::string::npos) << what;
  }
}

// 2^26 texels pass the bound (this file then fails for its missing pixels);
// one row more is refused for its size before anything is allocated.
TEST(TextureFile, TheTexelBoundIsMetExactlyAndPassedByOneRow) {
  TemporaryDirectory directory;
  const auto header_only = [&](std::int64_t width, std::int64_t height) {
    const fs::path path = directory.path() / ("header_" + std::to_string(width) + "x" + std::to_string(height) + ".ppm");
    std::ofstream(path, std::ios::binary) << "P6\n" << width << " " << height << "\n255\n";
    return path;
  };
  const std::int64_t full_height = kMaxTexturePixels / kMaxTextureSide;
  const std::string at_bound = read_error(header_only(kMaxTextureSide, full_height));
  EXPECT_EQ(at_bound.find("exceeds the limit"), std::string::npos) << at_bound;
  EXPECT_NE(at_bound.find("cannot read the pixels"), std::string::npos) << at_bound;
  const std::string past = read_error(header_only(kMaxTextureSide, full_height + 1));
  EXPECT_NE(past.find("exceeds the limit of 32768 texels per side and 67108864 texels in total"), std::string::npos)
      << past;
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

// Bytes this process has read through read(2) and the like (Linux
// /proc/self/io "rchar"), or -1.
long long bytes_read_so_far() {
  std::ifstream io("/proc/self/io");
  std::string key;
  long long value = 0;
  while (io >> key >> value) {
    if (key == "rchar:") return value;
  }
  return -1;
}

// OpenImageIO, given a file no plugin claims, tries every plugin, some
// reading the whole file (10 MB of zeros took 3.2 s): the first bytes
// decide instead, and the rest of the file is never read.
TEST(TextureFile, NonImagesAreRefusedFromTheirFirstBytes) {
  TemporaryDirectory directory;
  const std::size_t size = std::size_t{16} << 20;
  for (const char* name : {"zeros.png", "zeros.tga", "zeros"}) {
    const fs::path path = directory.path() / name;
    std::ofstream(path, std::ios::binary) << std::string(size, '\0');
    const long long before = bytes_read_so_far();
    ASSERT_GE(before, 0) << "cannot read rchar from /proc/self/io";
    const std::string what = read_error(path);
    EXPECT_LT(bytes_read_so_far() - before, 1 << 20) << name << " was read, not refused from its first bytes";
    EXPECT_EQ(what, path.string() + ": not an image: expected a " + std::string(kTextureFormatNames) +
                        " file, found first bytes '\\x00\\x00\\x00\\x00\\x00\\x00\\x00\\x00'");
  }
  const fs::path empty = directory.path() / "empty.png";
  std::ofstream{empty};
  EXPECT_NE(read_error(empty).find("not an image: expected a PNG, JPEG"), std::string::npos);
  EXPECT_NE(read_error(empty).find("found an empty file"), std::string::npos);
}

// Each listed format is read with the plugin its first bytes name, also
// under another format's extension.
TEST(TextureFile, EachFormatIsReadByItsFirstBytes) {
  TemporaryDirectory directory;
  const std::uint8_t pixels[6] = {10, 20, 30, 200, 210, 220};
  for (const char* name : {"a.png", "a.jpg", "a.tif", "a.exr", "a.hdr", "a.ppm", "a.bmp", "a.gif", "a.webp",
                           "a.tga"}) {
    SCOPED_TRACE(name);
    const fs::path path = directory.path() / name;
    write_with_oiio(path, 2, 1, 3, OIIO::TypeDesc::UINT8, pixels);
    const TextureImage image = read_texture_image(path);
    EXPECT_EQ(image.width, 2);
    EXPECT_EQ(image.height, 1);
  }
  const fs::path png_named_jpg = directory.path() / "png.jpg";
  fs::copy_file(directory.path() / "a.png", png_named_jpg);
  EXPECT_EQ(read_texture_image(png_named_jpg).rgb, read_texture_image(directory.path() / "a.png").rgb);

  // DDS, which OpenImageIO does not write: an uncompressed 1 x 1 BGR texel.
  std::string dds = "DDS ";
  auto word = [&dds](std::uint32_t value) {
    for (int i = 0; i < 4; ++i) dds += static_cast<char>((value >> (8 * i)) & 0xFF);
  };
  word(124);  // header size
  word(0x1 | 0x2 | 0x4 | 0x8 | 0x1000);  // caps, height, width, pitch and pixel format are set
  word(1);  // height
  word(1);  // width
  word(3);  // pitch
  for (int i = 0; i < 13; ++i) word(0);  // depth, mipmaps, reserved
  for (const std::uint32_t field : {32u, 0x40u, 0u, 24u}) word(field);  // pixel format: size, RGB, no FourCC, bits
  for (const std::uint32_t mask : {0xFF0000u, 0xFF00u, 0xFFu, 0u}) word(mask);  // R, G, B, A
  word(0x1000);  // a texture
  for (int i = 0; i < 4; ++i) word(0);  // caps 2 to 4, reserved
  dds += "\x03\x02\x01";  // B, G, R
  const fs::path dds_path = directory.path() / "a.dds";
  std::ofstream(dds_path, std::ios::binary) << dds;
  const TextureImage texel = read_texture_image(dds_path);
  EXPECT_EQ(texel.width, 1);
  EXPECT_EQ(texel.rgb, std::vector<float>({srgb_decoded(1), srgb_decoded(2), srgb_decoded(3)}));
}

// What `action` writes to this process's stderr (file descriptor 2, where
// libraries print), captured in a temporary file.
std::string printed_to_stderr(const std::function<void()>& action) {
  std::FILE* capture = std::tmpfile();
  if (capture == nullptr) {
    ADD_FAILURE() << "no temporary file";
    return {};
  }
  std::fflush(stderr);
  const int saved = ::dup(STDERR_FILENO);
  ::dup2(::fileno(capture), STDERR_FILENO);
  action();
  std::fflush(stderr);
  ::dup2(saved, STDERR_FILENO);
  ::close(saved);
  std::string printed;
  std::rewind(capture);
  for (int c = std::fgetc(capture); c != EOF; c = std::fgetc(capture)) printed += static_cast<char>(c);
  std::fclose(capture);
  return printed;
}

// libpng prints "libpng error: ..." to stderr as OpenImageIO decodes; that
// text belongs in the error, not on the terminal.
TEST(TextureFile, DecoderMessagesAreInTheErrorNotOnStderr) {
  TemporaryDirectory directory;
  std::vector<std::uint8_t> pixels(64 * 64 * 3);
  std::uint32_t state = 1;  // noise, so that the image data does not compress away
  for (std::uint8_t& p : pixels) {
    state = state * 1664525u + 1013904223u;
    p = static_cast<std::uint8_t>(state >> 24);
  }
  const fs::path whole = directory.path() / "whole.png";
  write_with_oiio(whole, 64, 64, 3, OIIO::TypeDesc::UINT8, pixels.data());
  std::ifstream in(whole, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 2000u);

  const fs::path cut = directory.path() / "cut.png";  // ends inside the image data
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  std::string broken = bytes;  // the first chunk after IHDR renamed to an invalid type
  broken[37] = '\x01';
  const fs::path bad_chunk = directory.path() / "bad_chunk.png";
  std::ofstream(bad_chunk, std::ios::binary) << broken;

  for (const fs::path& path : {cut, bad_chunk}) {
    std::string what;
    const std::string printed = printed_to_stderr([&] { what = read_error(path); });
    EXPECT_EQ(printed, "") << path.filename();
    EXPECT_NE(what.find("cannot "), std::string::npos) << what;
    EXPECT_NE(what.find("PNG"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;  // one line
  }
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
