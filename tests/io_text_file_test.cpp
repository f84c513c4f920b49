// Tests of io/text_file.h: a file of exactly the bound reads whole, one byte
// more is refused naming the file, the bound and its reason, also when the
// content outgrows the stated size; a file of several blocks reads whole;
// files that are missing or not regular files are refused naming the file.
#include "io/text_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include "io/parse_error.h"
#include "tests/support/temporary_directory.h"

namespace quiver {
namespace {

namespace fs = std::filesystem;

// The message of the ParseError read_text_file throws, or "" if it reads.
std::string refusal(const fs::path& path, std::size_t max_bytes, std::string_view reason = {}) {
  try {
    read_text_file(path, max_bytes, "a test file", reason);
  } catch (const ParseError& error) {
    return error.what();
  }
  return "";
}

TEST(TextFile, ReadsUpToTheBoundAndRefusesOneByteMore) {
  const testing::TemporaryDirectory temporary("quiver_text_file_test");
  const fs::path path = temporary.path() / "bounded.txt";
  const std::string text(100'000, 'x');  // more than one read chunk
  std::ofstream(path, std::ios::binary) << text;
  EXPECT_EQ(read_text_file(path, text.size(), "a test file").view(), text);
  EXPECT_EQ(refusal(path, text.size()), "");
  const std::string message = refusal(path, text.size() - 1, "the test's bound");
  EXPECT_NE(message.find(path.string()), std::string::npos) << message;
  EXPECT_NE(message.find("larger than the limit of 99999 bytes (the test's bound)"), std::string::npos) << message;
  // An empty file reads as empty, even with a bound of 0.
  const fs::path empty = temporary.path() / "empty.txt";
  std::ofstream(empty, std::ios::binary).flush();
  EXPECT_EQ(read_text_file(empty, 0, "a test file").view(), "");
}

// A file whose content outgrows its stated size (procfs states 0 bytes, a
// file may grow while read) is bounded while it is read, not only by size.
TEST(TextFile, AFileLongerThanItsStatedSizeIsBoundedWhileRead) {
  const fs::path kallsyms = "/proc/kallsyms";
  std::error_code error;
  std::ifstream in(kallsyms, std::ios::binary);
  if (!in || fs::file_size(kallsyms, error) != 0 || error) {
    GTEST_SKIP() << "needs Linux's /proc/kallsyms, readable and stated as 0 bytes";
  }
  std::string chunk(std::size_t{1} << 16, '\0');
  std::size_t length = 0;
  while (in) {
    in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
    length += static_cast<std::size_t>(in.gcount());
  }
  const std::size_t bound = 2 * chunk.size();  // more than one of the reader's chunks
  if (length <= 2 * bound) GTEST_SKIP() << "/proc/kallsyms holds only " << length << " bytes here";
  const std::string message = refusal(kallsyms, bound);
  EXPECT_NE(message.find("larger than the limit of " + std::to_string(bound) + " bytes"), std::string::npos)
      << message;
}

// A file of several blocks, read on several threads, comes back byte for byte.
TEST(TextFile, AFileOfManyBlocksReadsWhole) {
  const testing::TemporaryDirectory temporary("quiver_text_file_test");
  const fs::path path = temporary.path() / "blocks.bin";
  std::string bytes(2 * kFileReadBlockBytes + 12345, '\0');
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>((i * 2654435761u) >> 13);
  std::ofstream(path, std::ios::binary) << bytes;
  const FileBytes read = read_text_file(path, bytes.size(), "a test file");
  EXPECT_TRUE(read.view() == bytes);
  EXPECT_NE(refusal(path, bytes.size() - 1).find("larger than the limit"), std::string::npos);
}

TEST(TextFile, RefusesMissingFilesAndDirectories) {
  const testing::TemporaryDirectory temporary("quiver_text_file_test");
  for (const fs::path& path : {temporary.path() / "missing.txt", temporary.path()}) {
    const std::string message = refusal(path, 1000);
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace quiver
