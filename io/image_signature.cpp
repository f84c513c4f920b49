// Signatures from each format's specification (PNG 12.12, JFIF SOI + APPn,
// TIFF 6.0 header, OpenEXR magic 20000630, Radiance "#?" program line,
// Netpbm magic numbers, BMP "BM", GIF87a/89a, RIFF WEBP, "DDS "); TGA 2.0
// header fields for TGA. JPEG 2000 is left out: Debian 12's OpenImageIO
// 2.4.7 cannot read the JP2 files it writes ("Expected a SOC marker").
#include "io/image_signature.h"
#include "io/file_extension.h"

#include <array>
#include <cctype>
#include <string>

namespace quiver {

namespace {

using namespace std::string_view_literals;

struct Signature {
  std::string_view bytes;  // the file's first bytes
  std::string_view format;
};

constexpr std::array kSignatures{
    Signature{"\x89PNG\r\n\x1a\n"sv, "png"},
    Signature{"\xFF\xD8\xFF"sv, "jpeg"},
    Signature{"II*\0"sv, "tiff"},
    Signature{"MM\0*"sv, "tiff"},
    Signature{"II+\0"sv, "tiff"},  // BigTIFF
    Signature{"MM\0+"sv, "tiff"},
    Signature{"\x76\x2F\x31\x01"sv, "openexr"},
    Signature{"#?"sv, "hdr"},
    Signature{"BM"sv, "bmp"},
    Signature{"GIF87a"sv, "gif"},
    Signature{"GIF89a"sv, "gif"},
    Signature{"DDS "sv, "dds"},
};

bool has_at(std::string_view head, std::size_t offset, std::string_view bytes) {
  return head.size() >= offset + bytes.size() && head.substr(offset, bytes.size()) == bytes;
}

// WebP: a RIFF container (its size in bytes 4-7) of form type "WEBP".
bool is_webp(std::string_view head) { return has_at(head, 0, "RIFF") && has_at(head, 8, "WEBP"); }

// Netpbm: P1..P6 (bitmap, grey, pixel maps), Pf/PF (float), then a blank.
bool is_netpbm(std::string_view head) {
  if (head.size() < 3 || head[0] != 'P') return false;
  const char kind = head[1];
  const bool known = (kind >= '1' && kind <= '6') || kind == 'f' || kind == 'F';
  return known && std::isspace(static_cast<unsigned char>(head[2]));
}

// TGA 2.0: colour map type 0 or 1, an image type with data (1-3 plain,
// 9-11 run-length), non-zero width and height, a pixel depth it defines.
bool is_tga(std::string_view head, std::string_view extension) {
  if (ascii_lowercase(extension) != ".tga" || head.size() < kImageSignatureBytes) return false;
  auto byte = [&](std::size_t i) { return static_cast<unsigned char>(head[i]); };
  const unsigned type = byte(2);
  const unsigned width = byte(12) | (byte(13) << 8), height = byte(14) | (byte(15) << 8);
  const unsigned depth = byte(16);
  return byte(1) <= 1 && ((type >= 1 && type <= 3) || (type >= 9 && type <= 11)) && width > 0 && height > 0 &&
         (depth == 8 || depth == 15 || depth == 16 || depth == 24 || depth == 32);
}

}  // namespace

std::optional<std::string_view> image_format_of(std::string_view head, std::string_view extension) {
  for (const Signature& s : kSignatures) {
    if (has_at(head, 0, s.bytes)) return s.format;
  }
  if (is_webp(head)) return "webp";
  if (is_netpbm(head)) return "pnm";
  if (is_tga(head, extension)) return "targa";
  return std::nullopt;
}

}  // namespace quiver
