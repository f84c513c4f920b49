// Tests of io/oiio_loader.h and the quiver_oiio module's C-style interface
// (io/oiio_module.h): the module loads from beside this program, is of this
// version, and reports failures through return values and its message
// buffer instead of exceptions. A missing module is tested on the quiver
// program (app_cli_test.cpp), since a process loads it only once.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "io/oiio_loader.h"
#include "tests/support/temporary_directory.h"

namespace quiver {
namespace {

namespace fs = std::filesystem;

TEST(OiioModule, LoadsOnceWithThisVersion) {
  const OiioModuleApi& first = oiio_module();
  EXPECT_EQ(first.version, kOiioModuleVersion);
  EXPECT_EQ(&oiio_module(), &first);
}

TEST(OiioModule, FailuresAreReturnedWithAMessage) {
  const OiioModuleApi& oiio = oiio_module();
  testing::TemporaryDirectory directory;
  char error[256] = "";

  OiioImageHeader header{};
  const fs::path missing = directory.path() / "missing.png";
  EXPECT_EQ(oiio.open_input(missing.c_str(), "png", &header, error, sizeof error), nullptr);
  EXPECT_NE(std::string(error), "");

  const fs::path text = directory.path() / "text.png";
  std::ofstream(text) << "not an image\n";
  error[0] = '\0';
  EXPECT_EQ(oiio.open_input(text.c_str(), "png", &header, error, sizeof error), nullptr);
  EXPECT_NE(std::string(error), "");

  const std::vector<std::uint8_t> pixel{1, 2, 3};
  const char* names[] = {"R", "G", "B"};
  error[0] = '\0';
  EXPECT_EQ(oiio.write_image((directory.path() / "x.img").c_str(), "no-such-format", 1, 1, 3, names, 0,
                             pixel.data(), "sRGB", error, sizeof error),
            0);
  EXPECT_NE(std::string(error), "");

  // A format OpenImageIO has no plugin for.
  error[0] = '\0';
  EXPECT_EQ(oiio.open_input(text.c_str(), "no-such-format", &header, error, sizeof error), nullptr);
  EXPECT_NE(std::string(error), "");

  // A message longer than the buffer is cut and still terminated.
  char tiny[4] = {'x', 'x', 'x', 'x'};
  EXPECT_EQ(oiio.open_input(missing.c_str(), "png", &header, tiny, sizeof tiny), nullptr);
  EXPECT_EQ(tiny[3], '\0');
}

// A failing read's message: OpenImageIO's error, then each line its
// libraries printed to stderr that says something new, each thing once.
TEST(OiioModule, AFailingReadSaysEachThingOnce) {
  const OiioModuleApi& oiio = oiio_module();
  testing::TemporaryDirectory directory;
  const fs::path whole = fs::path(QUIVER_TEST_DATA_DIR) / "obj" / "tex" / "checker.png";
  std::ifstream in(whole, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 100u);
  const fs::path cut = directory.path() / "cut.png";
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);

  char error[1024] = "";
  OiioImageHeader header{};
  void* input = oiio.open_input(cut.c_str(), "png", &header, error, sizeof error);
  if (input != nullptr) {
    std::vector<std::uint8_t> pixels(std::size_t(header.width) * std::size_t(header.height) * 3 * 2);
    EXPECT_EQ(oiio.read_pixels(input, 3, 0, pixels.data(), 3 * 2, error, sizeof error), 0);
    oiio.close_input(input);
  }
  const std::string message = error;
  ASSERT_NE(message, "");
  // The parts after OpenImageIO's own error, each a printed line "library: text".
  std::vector<std::string> parts;
  for (std::size_t at = 0; at <= message.size();) {
    const std::size_t end = std::min(message.find("; ", at), message.size());
    parts.push_back(message.substr(at, end - at));
    at = end + 2;
  }
  for (std::size_t k = 1; k < parts.size(); ++k) {
    const std::size_t colon = parts[k].find(": ");
    const std::string text = colon == std::string::npos ? parts[k] : parts[k].substr(colon + 2);
    EXPECT_EQ(message.find(text), message.rfind(text)) << "said twice: '" << text << "' in: " << message;
  }
}

TEST(OiioModule, ReadsWhatItWrote) {
  const OiioModuleApi& oiio = oiio_module();
  testing::TemporaryDirectory directory;
  const fs::path path = directory.path() / "pixels.tif";
  const std::vector<float> written{0.25f, -1.5f, 3e10f, 0.f, 1.f, 2.f};
  const char* names[] = {"R", "G", "B"};
  char error[256] = "";
  ASSERT_EQ(oiio.write_image(path.c_str(), "tiff", 2, 1, 3, names, 1, written.data(), "Linear", error, sizeof error),
            1)
      << error;

  OiioImageHeader header{};
  void* input = oiio.open_input(path.c_str(), "tiff", &header, error, sizeof error);
  ASSERT_NE(input, nullptr) << error;
  EXPECT_EQ(header.width, 2);
  EXPECT_EQ(header.height, 1);
  EXPECT_EQ(header.depth, 1);
  EXPECT_EQ(header.channels, 3);
  EXPECT_EQ(header.is_float, 1);
  std::vector<float> read(6);
  EXPECT_EQ(oiio.read_pixels(input, 3, 1, read.data(), 3 * sizeof(float), error, sizeof error), 1) << error;
  oiio.close_input(input);
  EXPECT_EQ(read, written);
}

}  // namespace
}  // namespace quiver
