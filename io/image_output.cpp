// Framebuffer to image file: encode the pixels for the format, write them
// to a temporary file beside the target, then rename. PNG goes through
// libpng (zlib level 2) and OpenEXR through the OpenEXR library directly;
// JPEG, HDR and TIFF through OpenImageIO in the quiver_oiio module, loaded
// on first use.
#include "io/image_output.h"

#include "io/file_extension.h"
#include "io/oiio_loader.h"
#include "io/output_file.h"
#include "io/srgb_encoding.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <ImfStdIO.h>
#include <png.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <fstream>
#include <new>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace quiver {

namespace {

namespace fs = std::filesystem;

constexpr std::string_view kSupportedExtensions = ".png .jpg .jpeg .exr .hdr .tif .tiff";
// libjpeg's largest side; beyond it Debian's OpenImageIO 2.4 JPEG writer
// ends the process instead of reporting an error, so it is checked here.
constexpr int kMaxJpegSide = 65'500;

// Which library writes a format: libpng, OpenEXR, or OpenImageIO (module).
enum class Writer { png, openexr, oiio };

struct FormatInfo {
  std::string_view extension;
  std::string_view oiio_format;
  bool eight_bit_srgb;
  Writer writer;
};

constexpr std::array<FormatInfo, 7> kFormats{{
    {".png", "png", true, Writer::png},
    {".jpg", "jpeg", true, Writer::oiio},
    {".jpeg", "jpeg", true, Writer::oiio},
    {".exr", "openexr", false, Writer::openexr},
    {".hdr", "hdr", false, Writer::oiio},
    {".tif", "tiff", false, Writer::oiio},
    {".tiff", "tiff", false, Writer::oiio},
}};

[[noreturn]] void fail(const fs::path& path, std::string_view message) {
  std::string what = path.string();
  what += ": ";
  what += message;
  throw std::runtime_error(what);
}

const FormatInfo* format_of(const fs::path& path) {
  const std::string extension = lowercase_extension(path);
  for (const FormatInfo& format : kFormats) {
    if (format.extension == extension) return &format;
  }
  return nullptr;
}

bool has_aovs(const Framebuffer& framebuffer) {
  return !framebuffer.depth.empty() || !framebuffer.normal.empty() || !framebuffer.kind.empty() ||
         !framebuffer.id.empty();
}

// RGBE (Radiance HDR) holds no sign, NaN or infinity, and its exponent byte
// overflows near FLT_MAX: values are clamped to [0, kMaxRgbeValue], NaN is 0.
float rgbe_representable(float value) {
  constexpr float kMaxRgbeValue = 1e38f;
  return std::isnan(value) ? 0.f : std::clamp(value, 0.f, kMaxRgbeValue);
}

void check_sizes(const fs::path& path, const Framebuffer& framebuffer) {
  const std::size_t n = framebuffer.pixel_count();
  auto wrong = [&](std::string_view what) {
    throw std::invalid_argument(path.string() + ": framebuffer " + std::string(what) + " does not match its size " +
                                std::to_string(framebuffer.width) + " x " + std::to_string(framebuffer.height));
  };
  if (framebuffer.width < 1 || framebuffer.height < 1) wrong("extent");
  if (framebuffer.rgb.size() != 3 * n) wrong("rgb");
  if (!framebuffer.depth.empty() && framebuffer.depth.size() != n) wrong("depth");
  if (!framebuffer.normal.empty() && framebuffer.normal.size() != 3 * n) wrong("normal");
  if (!framebuffer.kind.empty() && framebuffer.kind.size() != n) wrong("kind");
  if (!framebuffer.id.empty() && framebuffer.id.size() != n) wrong("id");
}

// Channel names and interleaved float values: RGB, then each non-empty AOV.
std::vector<std::string> float_channel_names(const Framebuffer& framebuffer) {
  std::vector<std::string> names{"R", "G", "B"};
  if (!framebuffer.depth.empty()) names.push_back("Z");
  if (!framebuffer.normal.empty()) names.insert(names.end(), {"N.X", "N.Y", "N.Z"});
  if (!framebuffer.kind.empty()) names.push_back("kind");
  if (!framebuffer.id.empty()) names.push_back("id");
  return names;
}

std::vector<float> interleaved_floats(const Framebuffer& framebuffer, std::size_t channels) {
  const std::size_t n = framebuffer.pixel_count();
  std::vector<float> values(n * channels);
  for (std::size_t p = 0; p < n; ++p) {
    float* out = &values[p * channels];
    for (std::size_t c = 0; c < 3; ++c) *out++ = framebuffer.rgb[p * 3 + c];
    if (!framebuffer.depth.empty()) *out++ = framebuffer.depth[p];
    if (!framebuffer.normal.empty()) {
      for (std::size_t c = 0; c < 3; ++c) *out++ = framebuffer.normal[p * 3 + c];
    }
    if (!framebuffer.kind.empty()) *out++ = static_cast<float>(framebuffer.kind[p]);
    if (!framebuffer.id.empty()) *out++ = static_cast<float>(framebuffer.id[p]);
  }
  return values;
}

// zlib level of PNG files: a low level writes several times faster than
// libpng's default 6 for files a little larger, and writing is on the
// critical path of every render.
constexpr int kPngCompressionLevel = 2;

// libpng reports an error by calling this, which must not return: the
// message is kept and control goes back to write_png_rows' setjmp.
[[noreturn]] void png_error_exit(png_structp png, png_const_charp message) {
  auto* error = static_cast<char*>(png_get_error_ptr(png));
  std::snprintf(error, 256, "%s", message);
  png_longjmp(png, 1);
}

// Where write_png_rows puts the PNG's bytes: an open file, or a string.
struct PngSink {
  std::FILE* file = nullptr;
  std::string* bytes = nullptr;
};

// libpng's write callback; a short write or a failed allocation is a libpng error.
void write_to_sink(png_structp png, png_bytep data, png_size_t length) {
  auto* sink = static_cast<PngSink*>(png_get_io_ptr(png));
  bool written = true;
  if (sink->bytes != nullptr) {
    try {
      sink->bytes->append(reinterpret_cast<const char*>(data), length);
    } catch (const std::bad_alloc&) {
      written = false;  // libpng's error leaves by longjmp, never from inside a catch
    }
  } else {
    written = std::fwrite(data, 1, length, sink->file) == length;
  }
  if (!written) png_error(png, sink->bytes != nullptr ? "out of memory" : "write error");
}

void flush_sink(png_structp png) {
  auto* sink = static_cast<PngSink*>(png_get_io_ptr(png));
  if (sink->file != nullptr) std::fflush(sink->file);
}

// 8-bit RGB rows to a sink, tagged sRGB (perceptual intent). Only
// trivially destructible locals live here, as libpng's errors longjmp
// back into it; false with the message in error[256] on failure.
bool write_png_rows(PngSink* sink, int width, int height, const std::uint8_t* rgb, char* error) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, error, png_error_exit, nullptr);
  if (png == nullptr) {
    std::snprintf(error, 256, "out of memory");
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (info == nullptr || setjmp(png_jmpbuf(png))) {
    if (info == nullptr) std::snprintf(error, 256, "out of memory");
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_set_write_fn(png, sink, write_to_sink, flush_sink);
  png_set_compression_level(png, kPngCompressionLevel);
  png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  png_write_info(png, info);
  const std::size_t row_bytes = std::size_t(width) * 3;
  for (int y = 0; y < height; ++y) png_write_row(png, rgb + std::size_t(y) * row_bytes);
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return true;
}

void write_png(const fs::path& path, const fs::path& temporary, int width, int height,
               const std::vector<std::uint8_t>& rgb) {
  std::FILE* file = std::fopen(temporary.c_str(), "wb");
  if (file == nullptr) fail(path, "cannot create '" + temporary.string() + "'");
  char error[256] = "";
  PngSink sink{file, nullptr};
  const bool written = write_png_rows(&sink, width, height, rgb.data(), error);
  const bool closed = std::fclose(file) == 0;
  if (!written) fail(path, "cannot write: " + std::string(error));
  if (!closed) fail(path, "cannot finish '" + temporary.string() + "'");
}

// 32-bit float channels, zip-compressed scanlines, through OpenEXR. The
// stream is ours so that a failure to flush it on close is seen.
void write_openexr(const fs::path& path, const fs::path& temporary, int width, int height,
                   const std::vector<std::string>& names, const std::vector<float>& interleaved) {
  std::string error;
  try {
    Imf::Header header(width, height);
    header.compression() = Imf::ZIP_COMPRESSION;
    Imf::FrameBuffer slices;
    const std::size_t pixel_stride = names.size() * sizeof(float);
    for (std::size_t c = 0; c < names.size(); ++c) {
      header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
      // OpenEXR only reads through the slice's pointer when writing.
      char* first = const_cast<char*>(reinterpret_cast<const char*>(interleaved.data() + c));
      slices.insert(names[c], Imf::Slice(Imf::FLOAT, first, pixel_stride, pixel_stride * std::size_t(width)));
    }
    std::ofstream stream(temporary, std::ios::binary);
    if (!stream) {
      error = "cannot create '" + temporary.string() + "'";
    } else {
      {
        Imf::StdOFStream exr_stream(stream, temporary.c_str());
        Imf::OutputFile file(exr_stream, header);
        file.setFrameBuffer(slices);
        file.writePixels(height);
      }
      stream.close();
      if (stream.fail()) error = "cannot finish '" + temporary.string() + "'";
    }
  } catch (const std::exception& exception) {
    error = exception.what();
  }
  if (!error.empty()) fail(path, "cannot write: " + error);
}

// Any other format through OpenImageIO, in the quiver_oiio module.
void write_with_oiio(const fs::path& path, const fs::path& temporary, const FormatInfo& format, int width,
                     int height, const std::vector<std::string>& names, const void* pixels) {
  const OiioModuleApi* oiio = nullptr;
  try {
    oiio = &oiio_module();
  } catch (const std::runtime_error& error) {
    fail(path, "cannot write: " + std::string(error.what()));
  }
  std::vector<const char*> name_pointers;
  for (const std::string& name : names) name_pointers.push_back(name.c_str());
  char error[1024] = "";
  if (!oiio->write_image(temporary.c_str(), std::string(format.oiio_format).c_str(), width, height,
                         static_cast<int>(names.size()), name_pointers.data(), format.eight_bit_srgb ? 0 : 1, pixels,
                         format.eight_bit_srgb ? "sRGB" : "Linear", error, sizeof error)) {
    fail(path, "cannot write: " + std::string(error));
  }
}

}  // namespace

void check_output_path(const fs::path& path, bool with_aovs) {
  const FormatInfo* format = format_of(path);
  if (format == nullptr) {
    const std::string extension = path.extension().string();
    fail(path,
         (extension.empty() ? std::string("no image extension") : "unsupported image extension '" + extension + "'") +
             "; supported: " + std::string(kSupportedExtensions));
  }
  if (with_aovs && format->extension != ".exr") {
    fail(path, "AOVs need an OpenEXR file (.exr); supported: " + std::string(kSupportedExtensions));
  }
  check_output_directory(path);
}

void stage_image(StagedOutputs& outputs, const fs::path& path, const Framebuffer& framebuffer) {
  const bool with_aovs = has_aovs(framebuffer);
  check_output_path(path, with_aovs);
  check_sizes(path, framebuffer);
  const FormatInfo& format = *format_of(path);
  if (format.oiio_format == "jpeg" && (framebuffer.width > kMaxJpegSide || framebuffer.height > kMaxJpegSide)) {
    fail(path, "JPEG images hold at most " + std::to_string(kMaxJpegSide) + " pixels per side");
  }

  std::vector<std::uint8_t> bytes;
  std::vector<float> floats;
  std::vector<std::string> names{"R", "G", "B"};
  if (format.eight_bit_srgb) {
    bytes = srgb_rgb_bytes(framebuffer);
  } else {
    names = float_channel_names(framebuffer);
    floats = interleaved_floats(framebuffer, names.size());
    if (format.oiio_format == "hdr") {
      for (float& value : floats) value = rgbe_representable(value);
    }
  }

  outputs.stage(path, [&](const fs::path& temporary) {
    switch (format.writer) {
      case Writer::png:
        write_png(path, temporary, framebuffer.width, framebuffer.height, bytes);
        break;
      case Writer::openexr:
        write_openexr(path, temporary, framebuffer.width, framebuffer.height, names, floats);
        break;
      case Writer::oiio:
        write_with_oiio(path, temporary, format, framebuffer.width, framebuffer.height, names,
                        format.eight_bit_srgb ? static_cast<const void*>(bytes.data()) : floats.data());
        break;
    }
  });
}

std::vector<std::uint8_t> srgb_rgb_bytes(const Framebuffer& framebuffer) {
  std::vector<std::uint8_t> bytes(framebuffer.rgb.size());
  srgb_bytes(framebuffer.rgb, bytes);
  return bytes;
}

std::string encode_png(const Framebuffer& framebuffer) {
  const std::size_t n = framebuffer.pixel_count();
  if (framebuffer.width < 1 || framebuffer.height < 1 || framebuffer.rgb.size() != n * 3) {
    throw std::invalid_argument("encode_png: the framebuffer's colours do not match its size");
  }
  const std::vector<std::uint8_t> bytes = srgb_rgb_bytes(framebuffer);
  std::string png;
  char error[256] = "";
  PngSink sink{nullptr, &png};
  if (!write_png_rows(&sink, framebuffer.width, framebuffer.height, bytes.data(), error)) {
    throw std::runtime_error("cannot encode a PNG: " + std::string(error));
  }
  return png;
}

void write_image(const fs::path& path, const Framebuffer& framebuffer) {
  StagedOutputs outputs;
  stage_image(outputs, path, framebuffer);
  outputs.commit();
}

}  // namespace quiver
