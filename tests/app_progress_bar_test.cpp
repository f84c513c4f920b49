// The progress bar (app/progress_bar.h): silent when disabled or before its
// delay, redraws limited by its interval, a final line ending in a newline.
#include <chrono>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "app/progress_bar.h"

namespace quiver {
namespace {

using namespace std::chrono_literals;

// Everything written to a temporary FILE.
class Capture {
 public:
  Capture() : file_(std::tmpfile()) {}
  ~Capture() {
    if (file_) std::fclose(file_);
  }
  std::FILE* file() const { return file_; }
  std::string text() const {
    std::fflush(file_);
    std::rewind(file_);
    std::string out;
    for (int c = std::fgetc(file_); c != EOF; c = std::fgetc(file_)) out.push_back(char(c));
    return out;
  }

 private:
  std::FILE* file_;
};

std::size_t count(const std::string& text, char c) {
  std::size_t n = 0;
  for (char x : text) n += x == c ? 1 : 0;
  return n;
}

TEST(ProgressBar, DisabledWritesNothing) {
  Capture out;
  ASSERT_NE(out.file(), nullptr);
  ProgressBar bar(out.file(), false, 0s, 0s);
  bar.update(1, 4);
  bar.update(4, 4);
  bar.finish();
  EXPECT_FALSE(bar.drawn());
  EXPECT_EQ(out.text(), "");
}

TEST(ProgressBar, ShortRendersStaySilent) {
  Capture out;
  ASSERT_NE(out.file(), nullptr);
  ProgressBar bar(out.file(), true, 1h, 0s);
  bar.update(1, 2);
  bar.update(2, 2);
  bar.finish();
  EXPECT_EQ(out.text(), "");
}

TEST(ProgressBar, DrawsInPlaceAndEndsWithANewline) {
  Capture out;
  ASSERT_NE(out.file(), nullptr);
  ProgressBar bar(out.file(), true, 0s, 0s);
  bar.update(1, 4);
  bar.update(2, 4);
  bar.finish();
  const std::string text = out.text();
  EXPECT_TRUE(bar.drawn());
  EXPECT_EQ(count(text, '\r'), 3u);  // two updates and the final state
  EXPECT_EQ(count(text, '\n'), 1u);
  EXPECT_EQ(text.back(), '\n');
  EXPECT_NE(text.find(" 25%"), std::string::npos);
  EXPECT_NE(text.find("2/4 tiles"), std::string::npos);
  bar.finish();  // a second finish adds nothing
  EXPECT_EQ(out.text(), text);
}

TEST(ProgressBar, RedrawsAtMostOncePerInterval) {
  Capture out;
  ASSERT_NE(out.file(), nullptr);
  ProgressBar bar(out.file(), true, 0s, 1h);
  for (std::size_t done = 1; done <= 100; ++done) bar.update(done, 100);
  EXPECT_EQ(count(out.text(), '\r'), 1u);
  bar.finish();
  const std::string text = out.text();
  EXPECT_EQ(count(text, '\r'), 2u);
  EXPECT_NE(text.find("100%"), std::string::npos);  // the final state is drawn
  EXPECT_EQ(text.back(), '\n');
}

}  // namespace
}  // namespace quiver
