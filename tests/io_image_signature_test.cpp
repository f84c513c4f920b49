// Tests of io/image_signature.h: each texture format is told by its first
// bytes whatever the file's name, TGA by its name and header, and bytes of
// no format (zeros, text, a truncated signature) are no format.
#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <string_view>

#include "io/image_signature.h"

namespace quiver {
namespace {

using namespace std::string_view_literals;

// A head of kImageSignatureBytes: `start`, then zeros.
std::string head_of(std::string_view start) {
  std::string head(start);
  head.resize(kImageSignatureBytes, '\0');
  return head;
}

// A TGA header: uncompressed true colour, 2 x 3 pixels of 24 bits.
std::string tga_header() {
  std::string head(kImageSignatureBytes, '\0');
  head[2] = 2;
  head[12] = 2;
  head[14] = 3;
  head[16] = 24;
  return head;
}

TEST(ImageSignature, EachFormatIsToldByItsFirstBytes) {
  const struct {
    std::string_view start, format;
  } cases[] = {
      {"\x89PNG\r\n\x1a\n"sv, "png"},
      {"\xFF\xD8\xFF\xE0"sv, "jpeg"},
      {"II*\0"sv, "tiff"},
      {"MM\0*"sv, "tiff"},
      {"II+\0"sv, "tiff"},
      {"\x76\x2F\x31\x01"sv, "openexr"},
      {"#?RADIANCE\n"sv, "hdr"},
      {"#?RGBE\n"sv, "hdr"},
      {"BM"sv, "bmp"},
      {"GIF89a"sv, "gif"},
      {"GIF87a"sv, "gif"},
      {"RIFF\x10\0\0\0WEBPVP8 "sv, "webp"},
      {"DDS |\0\0\0"sv, "dds"},
      {"P6\n2 2\n255\n"sv, "pnm"},
      {"P1 1 1"sv, "pnm"},
      {"Pf\n1 1\n-1\n"sv, "pnm"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.format);
    EXPECT_EQ(image_format_of(head_of(c.start), ".png"), c.format);  // the name does not matter
    EXPECT_EQ(image_format_of(head_of(c.start), ""), c.format);
  }
}

TEST(ImageSignature, TgaNeedsItsExtensionAndAHeaderThatDescribesAnImage) {
  EXPECT_EQ(image_format_of(tga_header(), ".tga"), "targa");
  EXPECT_EQ(image_format_of(tga_header(), ".TGA"), "targa");
  EXPECT_EQ(image_format_of(tga_header(), ".png"), std::nullopt);
  // Every image type TGA defines, plain (1-3) and run-length (9-11), and
  // none next to them.
  for (const char type : {1, 2, 3, 9, 10, 11}) {
    std::string typed = tga_header();
    typed[2] = type;
    EXPECT_EQ(image_format_of(typed, ".tga"), "targa") << "type " << int(type);
  }
  for (const char type : {4, 8, 12}) {
    std::string typed = tga_header();
    typed[2] = type;
    EXPECT_EQ(image_format_of(typed, ".tga"), std::nullopt) << "type " << int(type);
  }
  const std::string zeros(kImageSignatureBytes, '\0');
  EXPECT_EQ(image_format_of(zeros, ".tga"), std::nullopt);  // image type 0: no image data
  // A colour map type, image type or depth TGA does not define; a zero side.
  const struct {
    std::size_t byte;
    char value;
  } bad_fields[] = {{1, 2}, {2, 0}, {2, 4}, {16, 12}, {12, 0}, {14, 0}};
  for (const auto& field : bad_fields) {
    std::string bad = tga_header();
    bad[field.byte] = field.value;
    EXPECT_EQ(image_format_of(bad, ".tga"), std::nullopt) << "byte " << field.byte;
  }
  EXPECT_EQ(image_format_of(tga_header().substr(0, 17), ".tga"), std::nullopt);  // a short file
}

TEST(ImageSignature, BytesOfNoFormatAreNoFormat) {
  for (const std::string_view head :
       {""sv, "\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0"sv, "not an image\n"sv, "\x89PNG\r\n"sv, "P7\n"sv, "P6"sv,
        "GIF90a"sv, "RIFF\x10\0\0\0WAVEfmt "sv, "\xFF\xD8"sv, "# comment\n"sv,
        "\0\0\0\x0CjP  \r\n\x87\n"sv}) {
    EXPECT_EQ(image_format_of(head, ".png"), std::nullopt) << ::testing::PrintToString(std::string(head));
  }
  // A head that ends after "P6" is not a pixel map, whatever lies past its end.
  const std::string buffer = "P6 2 2 255 ";
  EXPECT_EQ(image_format_of(std::string_view(buffer).substr(0, 2), ".ppm"), std::nullopt);
}

}  // namespace
}  // namespace quiver
