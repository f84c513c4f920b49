// The C-style interface of the quiver_oiio module (io/oiio_module.cpp), the
// shared library that holds every use of OpenImageIO. quiver loads it with
// dlopen on first use (io/oiio_loader.h), so a run that needs no
// OpenImageIO-only format never maps OpenImageIO and its ~260 dependencies.
// The module exports one function, kOiioModuleEntry, returning a table of
// plain functions; no C++ type or exception crosses the boundary. Every
// function reports failure by its return value and writes OpenImageIO's
// message, cut to fit and NUL-terminated, into the caller's error buffer.
// What the libraries below print to stderr while an image is read (libpng's
// "libpng error: ...") is captured: added to that message on failure,
// dropped on success.
#pragma once

#include <cstddef>

namespace quiver {

// Bumped whenever OiioModuleApi changes, so a stale module is refused.
inline constexpr int kOiioModuleVersion = 3;

// The exported symbol's name and file name of the module.
inline constexpr const char* kOiioModuleEntry = "quiver_oiio_module_api";
inline constexpr const char* kOiioModuleFileName = "quiver_oiio.so";

// What an opened image file holds, from its header.
struct OiioImageHeader {
  int width, height, depth, channels;
  int is_float;            // 1 when the pixels are stored as floating point
  char color_space[256];   // the "oiio:ColorSpace" attribute, empty when absent
};

struct OiioModuleApi {
  int version;  // kOiioModuleVersion

  // Writes width x height pixels of channel_count interleaved channels
  // (8-bit codes, or 32-bit floats when is_float) to path in the named
  // OpenImageIO format ("jpeg", "hdr", "tiff", ...), tagged with color_space.
  // Returns 1 on success, 0 with a message on failure.
  int (*write_image)(const char* path, const char* format, int width, int height, int channel_count,
                     const char* const* channel_names, int is_float, const void* pixels, const char* color_space,
                     char* error, std::size_t error_size);

  // Opens an image for reading with the plugin of the named OpenImageIO
  // format ("png", ...) alone, colours as stored (not premultiplied by
  // alpha), and fills header. Returns a handle for read_pixels and
  // close_input, or null with a message.
  void* (*open_input)(const char* path, const char* format, OiioImageHeader* header, char* error,
                      std::size_t error_size);

  // Reads the first channel_count channels of every pixel as 32-bit floats
  // (as_float) or 16-bit codes, pixel_stride bytes apart. Returns 1, or 0
  // with a message.
  int (*read_pixels)(void* input, int channel_count, int as_float, void* pixels, std::ptrdiff_t pixel_stride,
                     char* error, std::size_t error_size);

  // Closes the file and frees the handle.
  void (*close_input)(void* input);

  // As open_input, for the size bytes of an image file at data (which must
  // outlive the handle); name labels messages.
  void* (*open_memory_input)(const char* name, const void* data, std::size_t size, const char* format,
                             OiioImageHeader* header, char* error, std::size_t error_size);
};

}  // namespace quiver

// The one exported function (C linkage, name kOiioModuleEntry).
extern "C" const quiver::OiioModuleApi* quiver_oiio_module_api();
