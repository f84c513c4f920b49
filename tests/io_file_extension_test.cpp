#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "io/file_extension.h"

namespace quiver {
namespace {

// Every ASCII capital, A to Z, becomes its small letter; nothing else changes.
TEST(FileExtension, AsciiLowercaseLowersEveryCapitalAndNothingElse) {
  EXPECT_EQ(ascii_lowercase("ABCDEFGHIJKLMNOPQRSTUVWXYZ"), "abcdefghijklmnopqrstuvwxyz");
  EXPECT_EQ(ascii_lowercase("az09@[`{ .-_\xc3\x89"), "az09@[`{ .-_\xc3\x89");  // neighbours of the range, UTF-8 kept
  EXPECT_EQ(ascii_lowercase(""), "");
}

TEST(FileExtension, TheExtensionWithItsDotInLowerCase) {
  EXPECT_EQ(lowercase_extension(std::filesystem::path("dir.X/Model.OBJ")), ".obj");
  EXPECT_EQ(lowercase_extension(std::filesystem::path("scene.Toml")), ".toml");
  EXPECT_EQ(lowercase_extension(std::filesystem::path("ARCHIVE.TAR.GZ")), ".gz");
  EXPECT_EQ(lowercase_extension(std::filesystem::path("README")), "");
}

}  // namespace
}  // namespace quiver
