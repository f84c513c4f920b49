// The progress bar (app/progress_bar.h): silent when disabled or before its
// delay, redraws limited by its interval, a final line ending in a newline;
// in a log, whole lines; the time left from the tiles done.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "app/progress_bar.h"
#include "tests/support/captured_file.h"

namespace quiver {
namespace {

using namespace std::chrono_literals;

using Capture = testing::CapturedFile;

std::size_t count(const std::string& text, char c) {
  std::size_t n = 0;
  for (char x : text) n += x == c ? 1 : 0;
  return n;
}

TEST(ProgressBar, DisabledWritesNothing) {
  Capture out;
  ASSERT_NE(out.file(), nullptr);
  ProgressBar bar(out.file(), ProgressStyle::off, 0s, 0s);
  bar.update(1, 4, 0.25);
  bar.update(4, 4, 1.0);
  bar.finish();
  EXPECT_FALSE(bar.drawn());
  EXPECT_EQ(out.text(), "");
}

TEST(ProgressBar, ShortRendersStaySilent) {
  Capture out;
  ASSERT_NE(out.file(), nullptr);
  ProgressBar bar(out.file(), ProgressStyle::terminal, 1h, 0s);
  bar.update(1, 2, 0.5);
  bar.update(2, 2, 1.0);
  bar.finish();
  EXPECT_EQ(out.text(), "");
}

// What a bar without delay or interval writes for tiles 1 and 2 of 4, then
// finish() twice (the second must add nothing).
std::string two_updates_and_finish(ProgressStyle style, bool& drawn) {
  Capture out;
  if (out.file() == nullptr) return "no temporary file";
  ProgressBar bar(out.file(), style, 0s, 0s);
  bar.update(1, 4, 0.25);
  bar.update(2, 4, 0.5);
  bar.finish();
  bar.finish();
  drawn = bar.drawn();
  return out.text();
}

TEST(ProgressBar, DrawsInPlaceAndEndsWithANewline) {
  bool drawn = false;
  const std::string text = two_updates_and_finish(ProgressStyle::terminal, drawn);
  EXPECT_TRUE(drawn);
  EXPECT_EQ(count(text, '\r'), 3u);  // two updates and the final state, drawn once
  EXPECT_EQ(count(text, '\n'), 1u);
  EXPECT_EQ(text.back(), '\n');
  EXPECT_NE(text.find(" 25%"), std::string::npos);
  EXPECT_NE(text.find("2/4 tiles"), std::string::npos);
}

TEST(ProgressBar, RedrawsAtMostOncePerInterval) {
  Capture out;
  ASSERT_NE(out.file(), nullptr);
  ProgressBar bar(out.file(), ProgressStyle::terminal, 0s, 1h);
  for (std::size_t done = 1; done <= 100; ++done) bar.update(done, 100, double(done) / double(100));
  EXPECT_EQ(count(out.text(), '\r'), 1u);
  bar.finish();
  const std::string text = out.text();
  EXPECT_EQ(count(text, '\r'), 2u);
  EXPECT_NE(text.find("100%"), std::string::npos);  // the final state is drawn
  EXPECT_EQ(text.back(), '\n');
}

TEST(ProgressBar, ShowsTheTimeLeftUntilTheLastTile) {
  Capture out;
  ASSERT_NE(out.file(), nullptr);
  ProgressBar bar(out.file(), ProgressStyle::terminal, 0s, 0s);
  bar.update(1, 4, 0.25);
  EXPECT_NE(out.text().find(", ETA "), std::string::npos) << out.text();
  bar.update(4, 4, 1.0);
  bar.finish();
  const std::string text = out.text();
  const std::string last = text.substr(text.rfind('\r'));
  EXPECT_EQ(last.find("ETA"), std::string::npos) << last;  // done: no estimate
}

// The time left is judged by the pace of the work (work_seconds when given,
// not the elapsed time, which holds the setup before the first tile), with
// two significant digits below 10 s.
TEST(ProgressBar, TheTimeLeftFollowsThePaceOfTheWork) {
  Capture out;
  ASSERT_NE(out.file(), nullptr);
  ProgressBar bar(out.file(), ProgressStyle::log, 0s, 0s);
  std::this_thread::sleep_for(50ms);  // the elapsed time is now well above the work's
  bar.update(1, 4, 0.5, 0.004);
  bar.update(1, 4, 0.5, 0.03);
  bar.update(2, 4, 0.02, 0.04);
  bar.update(3, 4, 0.001, 0.04);
  bar.update(3, 4, 0.5, 5.0);  // more than elapsed: elapsed (0.05 s or a little more) wins
  const std::string text = out.text();
  EXPECT_NE(text.find(", ETA 0.00 s\n"), std::string::npos) << text;  // 0.004 s left
  EXPECT_NE(text.find(", ETA 0.03 s\n"), std::string::npos) << text;
  EXPECT_NE(text.find(", ETA 2.0 s\n"), std::string::npos) << text;
  EXPECT_NE(text.find(", ETA 40 s\n"), std::string::npos) << text;
  EXPECT_EQ(text.find(", ETA 5.0 s"), std::string::npos) << text;
  EXPECT_EQ(count(text, '\n'), 5u) << text;
}

// A second left exactly is the first figure of one decimal (the two-decimal
// form is for less than a second).
TEST(ProgressBar, OneSecondLeftReadsWithOneDecimal) {
  Capture out;
  ASSERT_NE(out.file(), nullptr);
  ProgressBar bar(out.file(), ProgressStyle::log, 0s, 0s);
  std::this_thread::sleep_for(1s);  // the elapsed time reaches the work's second
  bar.update(1, 4, 0.5, 1.0);       // half the work in one second: one second left
  const std::string text = out.text();
  EXPECT_NE(text.find(", ETA 1.0 s\n"), std::string::npos) << text;
}

TEST(ProgressBar, ALogGetsWholeLinesAndNothingAtTheEnd) {
  bool drawn = false;
  const std::string text = two_updates_and_finish(ProgressStyle::log, drawn);
  EXPECT_TRUE(drawn);
  EXPECT_EQ(count(text, '\r'), 0u);
  EXPECT_EQ(count(text, '\n'), 2u);  // one per update; finish adds none
  EXPECT_EQ(text.rfind("quiver: 25%, 1/4 tiles, ", 0), 0u) << text;
  EXPECT_NE(text.find("\nquiver: 50%, 2/4 tiles, "), std::string::npos) << text;
  EXPECT_NE(text.find(" s, ETA "), std::string::npos) << text;
}

TEST(ProgressBar, ALogWaitsForItsInterval) {
  Capture out;
  ASSERT_NE(out.file(), nullptr);
  ProgressBar bar(out.file(), ProgressStyle::log, 1h, 0s);
  for (std::size_t done = 1; done <= 10; ++done) bar.update(done, 10, double(done) / double(10));
  bar.finish();
  EXPECT_EQ(out.text(), "");
}

TEST(SecondsLeft, TheRemainingWorkAtTheDoneWorksPace) {
  EXPECT_EQ(seconds_left(0.0, 3.0), std::nullopt);
  EXPECT_EQ(seconds_left(std::nan(""), 3.0), std::nullopt);
  EXPECT_DOUBLE_EQ(*seconds_left(0.25, 2.0), 6.0);
  EXPECT_DOUBLE_EQ(*seconds_left(0.75, 3.0), 1.0);
  EXPECT_DOUBLE_EQ(*seconds_left(1.0, 9.0), 0.0);
  EXPECT_DOUBLE_EQ(*seconds_left(1.5, 9.0), 0.0);
}

TEST(ProgressBar, TheTimeLeftFollowsTheWorkNotTheTileCount) {
  Capture out;
  ASSERT_NE(out.file(), nullptr);
  ProgressBar bar(out.file(), ProgressStyle::log, 0s, 0s);
  bar.update(1, 2, 0.0);  // a tile of no estimated work: no estimate yet
  bar.update(1, 2, 1e-300);
  const std::string text = out.text();
  const std::size_t second = text.find('\n') + 1;
  EXPECT_EQ(text.substr(0, second).find("ETA"), std::string::npos) << text;
  EXPECT_NE(text.find("ETA ", second), std::string::npos) << text;
}

TEST(ProgressStyleFor, QuietIsOffAFileIsALog) {
  Capture out;
  ASSERT_NE(out.file(), nullptr);
  EXPECT_EQ(progress_style_for(out.file(), true), ProgressStyle::off);
  EXPECT_EQ(progress_style_for(out.file(), false), ProgressStyle::log);
  EXPECT_EQ(progress_style_for(nullptr, false), ProgressStyle::off);
}

}  // namespace
}  // namespace quiver
