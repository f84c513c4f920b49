// The quiver_oiio module: OpenImageIO behind the plain function table of
// io/oiio_module.h (JPEG/HDR/TIFF output and texture input). Built as a
// shared module that quiver dlopens on first use; nothing here throws.
#include "io/oiio_module.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <exception>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "io/module_message.h"

namespace quiver {

namespace {

// Sends what is printed to stderr while it lives (libpng, under
// OpenImageIO, prints "libpng error: ..." there) to a memory file, so that
// it can join the message instead of reaching the terminal. stderr is one
// per process: captures take turns.
class StderrCapture {
 public:
  StderrCapture() : lock_(turn()) {
    std::fflush(stderr);
    file_ = ::memfd_create("quiver_oiio_stderr", MFD_CLOEXEC);
    if (file_ >= 0) saved_ = ::dup(STDERR_FILENO);
    if (saved_ >= 0 && ::dup2(file_, STDERR_FILENO) < 0) {
      ::close(saved_);
      saved_ = -1;
    }
  }
  StderrCapture(const StderrCapture&) = delete;
  StderrCapture& operator=(const StderrCapture&) = delete;
  ~StderrCapture() {
    finish();
    if (file_ >= 0) ::close(file_);
  }

  // Restores stderr; returns what was printed (its first 4 KiB).
  std::string finish() {
    if (saved_ < 0) return {};
    std::fflush(stderr);
    ::dup2(saved_, STDERR_FILENO);
    ::close(saved_);
    saved_ = -1;
    std::string printed(4096, '\0');
    const ssize_t got = ::pread(file_, printed.data(), printed.size(), 0);
    printed.resize(got > 0 ? static_cast<std::size_t>(got) : 0);
    return printed;
  }

 private:
  static std::mutex& turn() {
    static std::mutex mutex;
    return mutex;
  }

  std::lock_guard<std::mutex> lock_;
  int file_ = -1;
  int saved_ = -1;
};

// message, then each printed line whose text (after a "library error: "
// prefix) it does not hold already.
std::string with_printed(std::string message, std::string_view printed) {
  while (!printed.empty()) {
    const std::size_t end = std::min(printed.find('\n'), printed.size());
    const std::string_view line = printed.substr(0, end);
    printed.remove_prefix(std::min(end + 1, printed.size()));
    const std::size_t colon = line.find(": ");
    const std::string_view text = colon == std::string_view::npos ? line : line.substr(colon + 2);
    if (!text.empty() && message.find(text) == std::string::npos) {
      message += "; ";
      message += line;
    }
  }
  return message;
}

// The error of an ImageInput or ImageOutput, else OpenImageIO's global one.
template <class ImageFile>
std::string error_of(ImageFile* file) {
  std::string message = file != nullptr ? file->geterror() : std::string();
  if (message.empty()) message = OIIO::geterror();
  return message.empty() ? std::string("unknown OpenImageIO error") : message;
}

int write_image(const char* path, const char* format, int width, int height, int channel_count,
                const char* const* channel_names, int is_float, const void* pixels, const char* color_space,
                char* error, std::size_t error_size) {
  try {
    const OIIO::TypeDesc type = is_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8;
    OIIO::ImageSpec spec(width, height, channel_count, type);
    spec.channelnames.assign(channel_names, channel_names + channel_count);
    spec.alpha_channel = -1;
    spec.attribute("oiio:ColorSpace", color_space);
    auto output = OIIO::ImageOutput::create(format);
    if (!output) {
      copy_message(error_of<OIIO::ImageOutput>(nullptr), error, error_size);
      return 0;
    }
    if (!output->open(path, spec) || !output->write_image(type, pixels) || !output->close()) {
      copy_message(error_of(output.get()), error, error_size);
      return 0;
    }
    return 1;
  } catch (const std::exception& exception) {
    copy_message(exception.what(), error, error_size);
    return 0;
  }
}

// An opened image: its ImageInput and, when it reads from memory, the
// proxy that serves it the bytes.
struct Input {
  std::unique_ptr<OIIO::Filesystem::IOMemReader> memory;
  std::unique_ptr<OIIO::ImageInput> image;
};

// Opens `name` with the format's plugin alone (ImageInput::open would try
// every plugin on a file its own plugin refuses), from the bytes at data
// when data is not null, and fills header.
void* open_any_input(const char* name, const void* data, std::size_t size, const char* format,
                     OiioImageHeader* header, char* error, std::size_t error_size) {
  try {
    auto input = std::make_unique<Input>();
    // Colours as stored: OpenImageIO would otherwise premultiply them by alpha.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    input->image = OIIO::ImageInput::create(format, false, &config);
    if (!input->image) {
      copy_message(error_of<OIIO::ImageInput>(nullptr), error, error_size);
      return nullptr;
    }
    if (data != nullptr) {
      input->memory = std::make_unique<OIIO::Filesystem::IOMemReader>(data, size);
      if (!input->image->set_ioproxy(input->memory.get())) {
        copy_message(std::string("the ") + format + " reader cannot read from memory", error, error_size);
        return nullptr;
      }
    }
    OIIO::ImageSpec spec;
    StderrCapture printed;
    if (!input->image->open(name, spec, config)) {
      copy_message(with_printed(error_of(input->image.get()), printed.finish()), error, error_size);
      return nullptr;
    }
    header->width = spec.width;
    header->height = spec.height;
    header->depth = spec.depth;
    header->channels = spec.nchannels;
    header->is_float = spec.format.is_floating_point() ? 1 : 0;
    copy_message(spec.get_string_attribute("oiio:ColorSpace"), header->color_space, sizeof header->color_space);
    return input.release();
  } catch (const std::exception& exception) {
    copy_message(exception.what(), error, error_size);
    return nullptr;
  }
}

void* open_input(const char* path, const char* format, OiioImageHeader* header, char* error,
                 std::size_t error_size) {
  return open_any_input(path, nullptr, 0, format, header, error, error_size);
}

void* open_memory_input(const char* name, const void* data, std::size_t size, const char* format,
                        OiioImageHeader* header, char* error, std::size_t error_size) {
  return open_any_input(name, data, size, format, header, error, error_size);
}

int read_pixels(void* handle, int channel_count, int as_float, void* pixels, std::ptrdiff_t pixel_stride, char* error,
                std::size_t error_size) {
  OIIO::ImageInput* input = static_cast<Input*>(handle)->image.get();
  try {
    const OIIO::TypeDesc type = as_float ? OIIO::TypeFloat : OIIO::TypeDesc::UINT16;
    StderrCapture printed;
    if (!input->read_image(0, 0, 0, channel_count, type, pixels, pixel_stride)) {
      copy_message(with_printed(error_of(input), printed.finish()), error, error_size);
      return 0;
    }
    return 1;
  } catch (const std::exception& exception) {
    copy_message(exception.what(), error, error_size);
    return 0;
  }
}

void close_input(void* handle) {
  std::unique_ptr<Input> input(static_cast<Input*>(handle));
  input->image->close();
}

constexpr OiioModuleApi kApi{kOiioModuleVersion, write_image, open_input, read_pixels, close_input, open_memory_input};

}  // namespace

}  // namespace quiver

extern "C" __attribute__((visibility("default"))) const quiver::OiioModuleApi* quiver_oiio_module_api() {
  return &quiver::kApi;
}
