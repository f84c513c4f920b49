// The status line before a render (app/stage_status.h): on a terminal each
// step is drawn in place with its time once it has lasted the delay, a
// shorter line clears what a longer one left, and the end erases the line
// and draws nothing more; before the delay, and anywhere but a terminal,
// nothing is written.
#include "app/stage_status.h"

#include <chrono>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "app/interrupt.h"
#include "tests/support/captured_file.h"

namespace quiver {
namespace {

using namespace std::chrono_literals;

TEST(StageStatus, ATerminalSeesEachStepInPlaceThenAnErasedLine) {
  testing::CapturedFile out;
  {
    StageStatus status(out.file(), ProgressStyle::terminal, 0ms, 2ms);
    status.begin("reading a long scene name.ply");
    std::this_thread::sleep_for(40ms);
    status.begin("building it");
    std::this_thread::sleep_for(40ms);
    EXPECT_TRUE(status_line_shown()) << "a signal now would start its message on a new line";
    status.end();
    EXPECT_FALSE(status_line_shown());
    const std::string text = out.text();
    const std::size_t reading = text.find("\rreading a long scene name.ply: "), building = text.find("\rbuilding it: ");
    ASSERT_NE(reading, std::string::npos) << text;
    ASSERT_NE(building, std::string::npos) << text;
    EXPECT_LT(reading, building);
    // The shorter line is padded over the longer one; the end blanks the widest and returns.
    const std::size_t widest = std::string("reading a long scene name.ply: 0.0 s").size();
    EXPECT_EQ(text.find('\r', building + 1) - building - 1, widest) << text;
    const std::string erased = "\r" + std::string(widest, ' ') + "\r";
    ASSERT_GE(text.size(), erased.size());
    EXPECT_EQ(text.substr(text.size() - erased.size()), erased);
    EXPECT_EQ(text.find('\n'), std::string::npos) << "never a line of its own";
    status.begin("after the end");
    std::this_thread::sleep_for(20ms);
  }
  EXPECT_EQ(out.text().find("after the end"), std::string::npos);
}

TEST(StageStatus, NothingBeforeTheDelay) {
  testing::CapturedFile out;
  {
    StageStatus status(out.file(), ProgressStyle::terminal, 1h, 2ms);
    status.begin("reading");
    std::this_thread::sleep_for(30ms);
  }
  EXPECT_EQ(out.text(), "");
}

TEST(StageStatus, SilentInALogOrWhenOff) {
  for (const ProgressStyle style : {ProgressStyle::log, ProgressStyle::off}) {
    testing::CapturedFile out;
    {
      StageStatus status(out.file(), style, 0ms, 2ms);
      status.begin("reading");
      std::this_thread::sleep_for(30ms);
    }
    EXPECT_EQ(out.text(), "") << int(style);
  }
}

}  // namespace
}  // namespace quiver
