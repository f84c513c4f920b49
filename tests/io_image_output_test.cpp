// Tests of io/image_output.h: each format written and read back with
// OpenImageIO (sRGB bytes, float exactness, AOV channels by name; PNG and
// OpenEXR come from the direct libpng and OpenEXR writers, the others from
// the quiver_oiio module), path checks, and failed writes that leave the
// directory as it was.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "integrator/framebuffer.h"
#include "io/image_output.h"
#include "tests/support/temporary_directory.h"

namespace quiver {
namespace {

namespace fs = std::filesystem;

constexpr float kInf = std::numeric_limits<float>::infinity();

using testing::TemporaryDirectory;

struct ReadBack {
  int width = 0, height = 0;
  std::vector<std::string> channel_names;
  std::string color_space, compression;  // OpenImageIO's "oiio:ColorSpace" and "compression"
  std::vector<float> floats;        // as float
  std::vector<std::uint8_t> bytes;  // as 8-bit codes
};

ReadBack read_back(const fs::path& path) {
  ReadBack image;
  auto input = OIIO::ImageInput::open(path.string());
  if (!input) {
    ADD_FAILURE() << "cannot read back " << path << ": " << OIIO::geterror();
    return image;
  }
  const OIIO::ImageSpec& spec = input->spec();
  image.width = spec.width;
  image.height = spec.height;
  image.channel_names = spec.channelnames;
  image.color_space = spec.get_string_attribute("oiio:ColorSpace");
  image.compression = spec.get_string_attribute("compression");
  const std::size_t values = spec.image_pixels() * std::size_t(spec.nchannels);
  image.floats.resize(values);
  image.bytes.resize(values);
  EXPECT_TRUE(input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeFloat, image.floats.data())) << input->geterror();
  EXPECT_TRUE(input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, image.bytes.data()))
      << input->geterror();
  return image;
}

// The values of one named channel, pixel by pixel.
std::vector<float> channel(const ReadBack& image, const std::string& name) {
  const auto found = std::find(image.channel_names.begin(), image.channel_names.end(), name);
  if (found == image.channel_names.end()) {
    ADD_FAILURE() << "no channel " << name;
    return {};
  }
  const std::size_t index = std::size_t(found - image.channel_names.begin());
  const std::size_t count = image.channel_names.size();
  std::vector<float> values;
  for (std::size_t i = index; i < image.floats.size(); i += count) values.push_back(image.floats[i]);
  return values;
}

// The sRGB OETF as IEC 61966-2-1 defines it, clamped and rounded to a byte.
int srgb_byte(double linear) {
  const double c = std::clamp(linear, 0.0, 1.0);
  const double encoded = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
  return int(std::lround(encoded * 255.0));
}

std::set<std::string> directory_entries(const fs::path& directory) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(directory)) names.insert(entry.path().filename().string());
  return names;
}

std::string file_bytes(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

// The runtime_error message of calling f, which must start with "path: ".
template <class F>
std::string runtime_error_of(const fs::path& path, F f) {
  try {
    f();
  } catch (const std::runtime_error& error) {
    const std::string what = error.what();
    EXPECT_EQ(what.rfind(path.string() + ": ", 0), 0u) << what;
    return what;
  }
  ADD_FAILURE() << "no std::runtime_error for " << path;
  return {};
}

Framebuffer gradient(int width, int height) {
  Framebuffer framebuffer(width, height);
  for (std::size_t i = 0; i < framebuffer.rgb.size(); ++i) framebuffer.rgb[i] = float(i % 17) / 8.f - 0.5f;
  return framebuffer;
}

// ---- formats ----

TEST(ImageOutput, PngIsSrgbEncodedClampedAndRounded) {
  TemporaryDirectory directory;
  const std::vector<float> linear{0.f, 0.5f, 1.f, 2.5f, -0.3f, 0.002f, 0.18f, 0.0031308f, 0.9999f};
  Framebuffer framebuffer(3, 1);
  framebuffer.rgb = linear;
  const fs::path path = directory.path() / "image.png";
  write_image(path, framebuffer);
  const ReadBack image = read_back(path);
  ASSERT_EQ(image.width, 3);
  ASSERT_EQ(image.height, 1);
  ASSERT_EQ(image.channel_names.size(), 3u);
  ASSERT_EQ(image.bytes.size(), linear.size());
  for (std::size_t i = 0; i < linear.size(); ++i) EXPECT_EQ(int(image.bytes[i]), srgb_byte(linear[i])) << linear[i];
  EXPECT_EQ(image.bytes[0], 0);
  EXPECT_EQ(image.bytes[1], 188);
  EXPECT_EQ(image.bytes[2], 255);
  EXPECT_EQ(image.bytes[3], 255);
  EXPECT_EQ(image.bytes[4], 0);
  EXPECT_EQ(directory_entries(directory.path()), (std::set<std::string>{"image.png"}));
}

TEST(ImageOutput, PngHoldsEveryByteCodeExactlyAndIsTaggedSrgb) {
  TemporaryDirectory directory;
  // Each code's own linear value, and the midpoints between neighbouring
  // codes' linear values, which must round to the nearer code.
  auto decoded = [](int code) {  // the sRGB EOTF of an 8-bit code
    const double c = code / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
  };
  Framebuffer framebuffer(256, 2);
  for (int code = 0; code < 256; ++code) {
    const double linear = decoded(code), linear_next = decoded(std::min(code + 1, 255));
    for (int k = 0; k < 3; ++k) {
      framebuffer.rgb[std::size_t(code) * 3 + std::size_t(k)] = float(linear);
      framebuffer.rgb[std::size_t(256 + code) * 3 + std::size_t(k)] = float(0.25 * linear + 0.75 * linear_next);
    }
  }
  const fs::path path = directory.path() / "codes.png";
  write_image(path, framebuffer);
  const ReadBack image = read_back(path);
  ASSERT_EQ(image.width, 256);
  ASSERT_EQ(image.height, 2);
  ASSERT_EQ(image.bytes.size(), framebuffer.rgb.size());
  for (std::size_t i = 0; i < 256 * 3; ++i) EXPECT_EQ(int(image.bytes[i]), int(i / 3)) << i;
  for (std::size_t i = 0; i < image.bytes.size(); ++i) {
    EXPECT_EQ(int(image.bytes[i]), srgb_byte(framebuffer.rgb[i])) << i;
  }
  EXPECT_EQ(image.color_space, "sRGB");
  EXPECT_EQ(directory_entries(directory.path()), (std::set<std::string>{"codes.png"}));
}

TEST(ImageOutput, ExrKeepsEveryFloatBitZipCompressed) {
  TemporaryDirectory directory;
  const std::vector<float> special{-0.f,
                                   std::numeric_limits<float>::denorm_min(),
                                   -std::numeric_limits<float>::denorm_min(),
                                   std::numeric_limits<float>::max(),
                                   -std::numeric_limits<float>::max(),
                                   kInf,
                                   -kInf,
                                   std::bit_cast<float>(0x7fc0'0001u),  // a NaN with a payload
                                   std::nextafter(1.f, 2.f),
                                   0.1f,
                                   -123.456f,
                                   1e-38f};
  Framebuffer framebuffer(2, 2);
  framebuffer.rgb = special;
  framebuffer.depth = {kInf, 0.5f, std::numeric_limits<float>::denorm_min(), 7.f};
  const fs::path path = directory.path() / "bits.exr";
  write_image(path, framebuffer);
  const ReadBack image = read_back(path);
  ASSERT_EQ(image.width, 2);
  ASSERT_EQ(image.height, 2);
  EXPECT_EQ(image.compression, "zip");
  const std::vector<float> red = channel(image, "R"), green = channel(image, "G"), blue = channel(image, "B");
  const std::vector<float> depth = channel(image, "Z");
  ASSERT_EQ(red.size(), 4u);
  ASSERT_EQ(depth.size(), 4u);
  for (std::size_t p = 0; p < 4; ++p) {
    EXPECT_EQ(std::bit_cast<std::uint32_t>(red[p]), std::bit_cast<std::uint32_t>(special[p * 3])) << p;
    EXPECT_EQ(std::bit_cast<std::uint32_t>(green[p]), std::bit_cast<std::uint32_t>(special[p * 3 + 1])) << p;
    EXPECT_EQ(std::bit_cast<std::uint32_t>(blue[p]), std::bit_cast<std::uint32_t>(special[p * 3 + 2])) << p;
    EXPECT_EQ(std::bit_cast<std::uint32_t>(depth[p]), std::bit_cast<std::uint32_t>(framebuffer.depth[p])) << p;
  }
  EXPECT_EQ(directory_entries(directory.path()), (std::set<std::string>{"bits.exr"}));
}

TEST(ImageOutput, JpegIsReadableAtTheRightSize) {
  TemporaryDirectory directory;
  Framebuffer framebuffer(16, 8);
  std::fill(framebuffer.rgb.begin(), framebuffer.rgb.end(), 0.5f);
  const fs::path path = directory.path() / "image.JPG";
  write_image(path, framebuffer);
  const ReadBack image = read_back(path);
  EXPECT_EQ(image.width, 16);
  EXPECT_EQ(image.height, 8);
  ASSERT_EQ(image.bytes.size(), 16u * 8u * 3u);
  for (std::uint8_t byte : image.bytes) EXPECT_NEAR(int(byte), 188, 2);
  // Beyond libjpeg's 65500-pixel side: an error, not the end of the process;
  // a side of exactly 65500 is written, on either axis.
  const fs::path wide = directory.path() / "wide.jpg";
  EXPECT_NE(runtime_error_of(wide, [&] { write_image(wide, Framebuffer(65'501, 1)); }).find("65500"),
            std::string::npos);
  const fs::path tall = directory.path() / "tall.jpg";
  EXPECT_NE(runtime_error_of(tall, [&] { write_image(tall, Framebuffer(1, 65'501)); }).find("65500"),
            std::string::npos);
  for (const auto& [width, height] : {std::pair{65'500, 1}, std::pair{1, 65'500}}) {
    const fs::path widest = directory.path() / ("widest_" + std::to_string(width) + ".jpg");
    write_image(widest, Framebuffer(width, height));
    const ReadBack read = read_back(widest);
    EXPECT_EQ(read.width, width);
    EXPECT_EQ(read.height, height);
  }
}

TEST(ImageOutput, ExrIsExactFloatWithAovChannels) {
  TemporaryDirectory directory;
  Framebuffer framebuffer = gradient(3, 2);
  framebuffer.rgb[4] = 1e-30f;
  framebuffer.rgb[5] = 12345.678f;
  framebuffer.depth = {1.5f, kInf, 0.1f, 1e6f, kInf, 3.25f};
  framebuffer.normal.resize(18);
  for (std::size_t i = 0; i < framebuffer.normal.size(); ++i) framebuffer.normal[i] = float(i) / 17.f - 0.5f;
  framebuffer.kind = {0, kNoKind, 2, 3, kNoKind, 4};
  framebuffer.id = {0, -1, 7, 16'777'216, -1, 12'345};
  const fs::path path = directory.path() / "image.exr";
  write_image(path, framebuffer);

  const ReadBack image = read_back(path);
  ASSERT_EQ(image.width, 3);
  ASSERT_EQ(image.height, 2);
  EXPECT_EQ(std::set<std::string>(image.channel_names.begin(), image.channel_names.end()),
            (std::set<std::string>{"R", "G", "B", "Z", "N.X", "N.Y", "N.Z", "kind", "id"}));
  const std::vector<float> red = channel(image, "R"), green = channel(image, "G"), blue = channel(image, "B");
  const std::vector<float> nx = channel(image, "N.X"), ny = channel(image, "N.Y"), nz = channel(image, "N.Z");
  const std::vector<float> kind = channel(image, "kind"), id = channel(image, "id");
  ASSERT_EQ(red.size(), 6u);
  ASSERT_EQ(kind.size(), 6u);
  ASSERT_EQ(id.size(), 6u);
  ASSERT_EQ(nz.size(), 6u);
  for (std::size_t p = 0; p < 6; ++p) {
    EXPECT_EQ(red[p], framebuffer.rgb[p * 3]);
    EXPECT_EQ(green[p], framebuffer.rgb[p * 3 + 1]);
    EXPECT_EQ(blue[p], framebuffer.rgb[p * 3 + 2]);
    EXPECT_EQ(nx[p], framebuffer.normal[p * 3]);
    EXPECT_EQ(ny[p], framebuffer.normal[p * 3 + 1]);
    EXPECT_EQ(nz[p], framebuffer.normal[p * 3 + 2]);
    EXPECT_EQ(kind[p], float(framebuffer.kind[p]));
    EXPECT_EQ(id[p], float(framebuffer.id[p]));
  }
  EXPECT_EQ(channel(image, "Z"), framebuffer.depth);
  EXPECT_EQ(kind[1], -1.f);
  EXPECT_EQ(id[3], 16777216.f);

  // Only the non-empty AOVs are written.
  Framebuffer depth_only = gradient(2, 2);
  depth_only.depth = {1.f, kInf, 2.f, 3.f};
  const fs::path depth_path = directory.path() / "depth.exr";
  write_image(depth_path, depth_only);
  const ReadBack depth_image = read_back(depth_path);
  EXPECT_EQ(std::set<std::string>(depth_image.channel_names.begin(), depth_image.channel_names.end()),
            (std::set<std::string>{"R", "G", "B", "Z"}));
  EXPECT_EQ(channel(depth_image, "Z"), depth_only.depth);
  const fs::path plain_path = directory.path() / "plain.exr";
  write_image(plain_path, gradient(2, 2));
  EXPECT_EQ(read_back(plain_path).channel_names, (std::vector<std::string>{"R", "G", "B"}));
}

TEST(ImageOutput, TiffIsExactAndHdrWithinRgbePrecision) {
  TemporaryDirectory directory;
  Framebuffer framebuffer = gradient(5, 3);
  framebuffer.rgb[0] = 1e-3f;
  framebuffer.rgb[1] = 1000.f;
  const fs::path tiff = directory.path() / "image.tif";
  write_image(tiff, framebuffer);
  const ReadBack tiff_image = read_back(tiff);
  EXPECT_EQ(tiff_image.width, 5);
  EXPECT_EQ(tiff_image.height, 3);
  EXPECT_EQ(tiff_image.floats, framebuffer.rgb);

  // RGBE: an 8-bit mantissa per channel with a shared exponent, so each
  // channel is within 1/128 of the pixel's largest channel; negatives and
  // NaN become 0, infinity 1e38.
  framebuffer.rgb[3] = std::numeric_limits<float>::quiet_NaN();
  framebuffer.rgb[4] = -2.f;
  framebuffer.rgb[5] = kInf;
  const fs::path hdr = directory.path() / "image.hdr";
  write_image(hdr, framebuffer);
  const ReadBack hdr_image = read_back(hdr);
  EXPECT_EQ(hdr_image.width, 5);
  EXPECT_EQ(hdr_image.height, 3);
  ASSERT_EQ(hdr_image.floats.size(), framebuffer.rgb.size());
  auto representable = [](float value) { return std::isnan(value) ? 0.f : std::clamp(value, 0.f, 1e38f); };
  for (std::size_t p = 0; p < framebuffer.pixel_count(); ++p) {
    const float* written = &framebuffer.rgb[p * 3];
    const float largest = std::max({representable(written[0]), representable(written[1]), representable(written[2])});
    for (std::size_t c = 0; c < 3; ++c) {
      EXPECT_NEAR(hdr_image.floats[p * 3 + c], representable(written[c]), largest / 128.f) << p << ", " << c;
    }
  }
  EXPECT_EQ(hdr_image.floats[3], 0.f);
  EXPECT_EQ(hdr_image.floats[4], 0.f);
  EXPECT_NEAR(hdr_image.floats[5], 1e38f, 1e38f / 128.f);
}

// ---- path checks ----

TEST(ImageOutputPath, AcceptsSupportedExtensionsInAnyCase) {
  TemporaryDirectory directory;
  for (const char* name : {"a.png", "a.PNG", "a.jpg", "a.Jpeg", "a.exr", "a.hdr", "a.tif", "a.TIFF"}) {
    EXPECT_NO_THROW(check_output_path(directory.path() / name, false)) << name;
  }
  EXPECT_NO_THROW(check_output_path(directory.path() / "aovs.EXR", true));
}

TEST(ImageOutputPath, RejectsBadExtensionsAovsWithoutExrAndMissingDirectories) {
  TemporaryDirectory directory;
  const fs::path bmp = directory.path() / "image.bmp";
  const std::string unknown = runtime_error_of(bmp, [&] { check_output_path(bmp, false); });
  EXPECT_NE(unknown.find("'.bmp'"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find(".png .jpg .jpeg .exr .hdr .tif .tiff"), std::string::npos) << unknown;
  const fs::path bare = directory.path() / "image";
  EXPECT_NE(runtime_error_of(bare, [&] { check_output_path(bare, false); }).find("no image extension"),
            std::string::npos);

  const fs::path png = directory.path() / "image.png";
  EXPECT_NE(runtime_error_of(png, [&] { check_output_path(png, true); }).find("AOVs need an OpenEXR file"),
            std::string::npos);
  Framebuffer with_depth(1, 1);
  with_depth.depth = {1.f};
  runtime_error_of(png, [&] { write_image(png, with_depth); });
  EXPECT_FALSE(fs::exists(png));

  const fs::path missing = directory.path() / "missing" / "image.png";
  EXPECT_NE(runtime_error_of(missing, [&] { check_output_path(missing, false); }).find("does not exist"),
            std::string::npos);
  const fs::path regular = directory.path() / "regular";
  std::ofstream(regular) << "x";
  const fs::path under_file = regular / "image.png";
  EXPECT_NE(runtime_error_of(under_file, [&] { check_output_path(under_file, false); }).find("is not a directory"),
            std::string::npos);
  const fs::path folder = directory.path() / "folder.png";
  fs::create_directory(folder);
  EXPECT_NE(runtime_error_of(folder, [&] { check_output_path(folder, false); }).find("is a directory"),
            std::string::npos);
}

// ---- failed writes leave the directory as it was ----

TEST(ImageOutputFailure, FailedWritesLeaveNoTemporaryAndKeepTheTarget) {
  TemporaryDirectory directory;
  const std::string kept = "existing bytes\n";
  const fs::path target = directory.path() / "image.png";
  std::ofstream(target, std::ios::binary) << kept;
  const std::set<std::string> before = directory_entries(directory.path());

  // libpng refuses widths beyond 1,000,000 once the temporary file is open.
  const std::string what = runtime_error_of(target, [&] { write_image(target, Framebuffer(1'000'001, 1)); });
  EXPECT_NE(what.find("cannot write"), std::string::npos) << what;
  EXPECT_EQ(file_bytes(target), kept);
  EXPECT_EQ(directory_entries(directory.path()), before);

  // The parent is a regular file: nothing is created anywhere.
  const fs::path under_file = target / "image.png";
  runtime_error_of(under_file, [&] { write_image(under_file, gradient(2, 2)); });
  EXPECT_EQ(file_bytes(target), kept);

  // The target is a directory: it stays one, with its contents.
  const fs::path folder = directory.path() / "folder.exr";
  fs::create_directory(folder);
  std::ofstream(folder / "inside") << "y";
  runtime_error_of(folder, [&] { write_image(folder, gradient(2, 2)); });
  EXPECT_TRUE(fs::is_directory(folder));
  EXPECT_EQ(file_bytes(folder / "inside"), "y");
  EXPECT_EQ(directory_entries(directory.path()), (std::set<std::string>{"image.png", "folder.exr"}));

  // Framebuffer arrays that do not match its size are a programming error.
  Framebuffer short_rgb(2, 2);
  short_rgb.rgb.pop_back();
  EXPECT_THROW(write_image(target, short_rgb), std::invalid_argument);
  Framebuffer short_ids = gradient(2, 2);
  short_ids.id = {1, 2, 3};
  EXPECT_THROW(write_image(directory.path() / "ids.exr", short_ids), std::invalid_argument);
  EXPECT_EQ(file_bytes(target), kept);

  // A successful write replaces the target and leaves nothing else.
  write_image(target, gradient(2, 2));
  EXPECT_EQ(read_back(target).width, 2);
  EXPECT_EQ(directory_entries(directory.path()), (std::set<std::string>{"image.png", "folder.exr"}));
}

}  // namespace
}  // namespace quiver
