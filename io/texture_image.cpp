// Texture images read through OpenImageIO (the quiver_oiio module) into
// linear RGB floats.
#include "io/texture_image.h"

#include <cctype>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "io/image_signature.h"
#include "io/oiio_loader.h"
#include "io/parse_error.h"

namespace quiver {

namespace {

namespace fs = std::filesystem;

// name: the file's path, or what holds the image ("mesh.glb (embedded image)").
[[noreturn]] void fail(std::string_view name, std::string_view message) { throw ParseError::whole_file(name, message); }

constexpr std::size_t kUint16Levels = 65'536;

// The sRGB EOTF (IEC 61966-2-1), encoded value in [0, 1] to linear.
double srgb_to_linear(double encoded) {
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

// Linear value of each 16-bit code of an sRGB-encoded channel. An 8-bit code
// c widens exactly to c * 257, and c * 257 / 65535 == c / 255.
const std::vector<float>& srgb_uint16_table() {
  static const std::vector<float> table = [] {
    std::vector<float> values(kUint16Levels);
    for (std::size_t code = 0; code < kUint16Levels; ++code) {
      values[code] = static_cast<float>(srgb_to_linear(double(code) / 65535.0));
    }
    return values;
  }();
  return table;
}

// True when the file's colour space metadata names a linear encoding.
bool names_linear_space(std::string color_space) {
  for (char& c : color_space) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return color_space.find("linear") != std::string::npos || color_space.rfind("lin_", 0) == 0 ||
         color_space == "acescg" || color_space == "aces2065-1";
}

// Copies the first channel of each texel into the other two (grey images).
void replicate_grey(std::vector<float>& rgb) {
  for (std::size_t i = 0; i < rgb.size(); i += 3) rgb[i + 1] = rgb[i + 2] = rgb[i];
}

void check_finite_texels(std::string_view path, const TextureImage& image) {
  for (std::size_t i = 0; i < image.rgb.size(); ++i) {
    if (!std::isfinite(image.rgb[i])) {
      const std::size_t texel = i / 3;
      const std::size_t width = static_cast<std::size_t>(image.width);
      fail(path, "texel (" + std::to_string(texel % width) + ", " + std::to_string(texel / width) +
                     ") is not finite (NaN or infinity)");
    }
  }
}

// The OpenImageIO format of an image's first bytes; an image they name no
// texture format of is refused before any decoder sees it.
std::string_view format_from_signature(std::string_view name, std::string_view head, std::string_view extension) {
  const std::optional<std::string_view> format = image_format_of(head, extension);
  if (!format) {
    const std::string found = head.empty() ? "an empty file" : "first bytes " + quoted_token(head.substr(0, 8));
    fail(name, joined({"not an image: expected a ", kTextureFormatNames, " file, found ", found}));
  }
  return *format;
}

const OiioModuleApi& oiio_or_fail(std::string_view name) {
  try {
    return oiio_module();
  } catch (const std::runtime_error& error) {
    fail(name, error.what());
  }
}

// The texels of an image opened with the module (header filled), bounds
// checked before anything is sized from the header.
TextureImage decode_opened(std::string_view name, const OiioModuleApi& oiio, void* opened,
                           const OiioImageHeader& header) {
  const std::unique_ptr<void, void (*)(void*)> input(opened, oiio.close_input);
  char error_text[1024] = "";
  const std::int64_t w = header.width, h = header.height;
  if (w < 1 || h < 1 || header.channels < 1) fail(name, "the image is empty");
  if (header.depth != 1) fail(name, "volume images (depth " + std::to_string(header.depth) + ") are not textures");
  if (w > kMaxTextureSide || h > kMaxTextureSide || w * h > kMaxTexturePixels) {
    fail(name, std::to_string(w) + " x " + std::to_string(h) + " texels exceeds " + texture_size_limit_text());
  }

  TextureImage image;
  image.width = header.width;
  image.height = header.height;
  const std::size_t texels = std::size_t(w * h);
  const int channels = header.channels >= 3 ? 3 : 1;  // grey (+ alpha) or RGB (+ alpha)
  image.rgb.resize(texels * 3);

  if (header.is_float) {
    // Linear floats straight into the RGB array; grey lands in the first slot.
    if (!oiio.read_pixels(input.get(), channels, 1, image.rgb.data(), 3 * sizeof(float), error_text,
                          sizeof error_text)) {
      fail(name, "cannot read the pixels (" + std::string(error_text) + ")");
    }
    if (channels == 1) replicate_grey(image.rgb);
    check_finite_texels(name, image);
  } else {
    // Integer codes widened to 16 bits (exact), then decoded per code.
    std::vector<std::uint16_t> codes(texels * std::size_t(channels));
    if (!oiio.read_pixels(input.get(), channels, 0, codes.data(), channels * std::ptrdiff_t(sizeof(std::uint16_t)),
                          error_text, sizeof error_text)) {
      fail(name, "cannot read the pixels (" + std::string(error_text) + ")");
    }
    const bool linear = names_linear_space(header.color_space);
    const std::vector<float>& srgb = srgb_uint16_table();
    for (std::size_t t = 0; t < texels; ++t) {
      for (std::size_t c = 0; c < 3; ++c) {
        const std::uint16_t code = codes[t * std::size_t(channels) + (channels == 1 ? 0 : c)];
        image.rgb[t * 3 + c] = linear ? static_cast<float>(double(code) / 65535.0) : srgb[code];
      }
    }
  }
  return image;
}

}  // namespace

TextureImage read_texture_image(const fs::path& path) {
  const std::string name = path.string();
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (!fs::exists(status)) fail(name, "cannot open: no such file");
  if (fs::is_directory(status)) fail(name, "cannot open: it is a directory");
  // A FIFO, socket or device could block or never end.
  if (!fs::is_regular_file(status)) fail(name, "cannot open: not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(name, "cannot open it");
  std::string head(kImageSignatureBytes, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  const std::string format(format_from_signature(name, head, path.extension().string()));

  const OiioModuleApi& oiio = oiio_or_fail(name);
  char error_text[1024] = "";
  OiioImageHeader header{};
  void* opened = oiio.open_input(path.c_str(), format.c_str(), &header, error_text, sizeof error_text);
  if (opened == nullptr) fail(name, joined({"cannot decode it as ", format, " (", error_text, ")"}));
  return decode_opened(name, oiio, opened, header);
}

TextureImage decode_texture_image(std::span<const std::uint8_t> bytes, std::string_view name) {
  const std::string_view all(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  const std::string format(format_from_signature(name, all.substr(0, kImageSignatureBytes), ""));
  const OiioModuleApi& oiio = oiio_or_fail(name);
  char error_text[1024] = "";
  OiioImageHeader header{};
  const std::string label(name);
  void* opened = oiio.open_memory_input(label.c_str(), bytes.data(), bytes.size(), format.c_str(), &header,
                                        error_text, sizeof error_text);
  if (opened == nullptr) fail(name, joined({"cannot decode it as ", format, " (", error_text, ")"}));
  return decode_opened(name, oiio, opened, header);
}

void read_texture_images(SceneDesc& scene) {
  for (TextureDesc& t : scene.textures) {
    if (t.kind != TextureDesc::Kind::image || !t.rgb.empty() || (t.path.empty() && t.encoded.empty())) continue;
    TextureImage image;
    try {
      image = t.encoded.empty() ? read_texture_image(t.path)
                                : decode_texture_image(t.encoded, t.named_at.file + " (embedded image)");
      std::vector<std::uint8_t>().swap(t.encoded);  // the texels replace the file's bytes
    } catch (const ParseError& error) {
      // An image file a mesh names as a whole (a glTF's): the mesh, then the image.
      if (t.named_at.line == 0 && !t.path.empty() && !t.named_at.file.empty()) {
        throw ParseError::whole_file(t.named_at.file, joined({"in the image texture it names: ", error.what()}));
      }
      if (t.named_at.line == 0) throw;
      throw ParseError::in_named_file(t.named_at, "image texture", error);
    }
    t.width = image.width;
    t.height = image.height;
    t.rgb = std::move(image.rgb);
  }
}

}  // namespace quiver
