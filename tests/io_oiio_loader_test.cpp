// Tests of io/oiio_loader.h and the quiver_oiio module's C-style interface
// (io/oiio_module.h): the module loads from beside this program, is of this
// version, and reports failures through return values and its message
// buffer instead of exceptions. A missing module is tested on the quiver
// program (app_cli_test.cpp), since a process loads it only once.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
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
