// SIGINT and SIGTERM handling (app/interrupt.h), each case in a child
// process (a death test), as signals and the stop flag are process-wide:
// while reading, a signal ends the process at once with 128 + the signal
// and one line; while rendering, the first signal raises the stop flag and
// is the one remembered; once ending, a signal exits with the code given
// and prints nothing.
#include <csignal>
#include <cstdlib>

#include <gtest/gtest.h>

#include "app/interrupt.h"

namespace quiver {
namespace {

TEST(InterruptDeathTest, WhileReadingASignalEndsTheProcessAtOnce) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        install_interrupt_handlers();
        std::raise(SIGINT);
        std::exit(0);
      },
      testing::ExitedWithCode(130), "quiver: interrupted by SIGINT while reading the scene; nothing written\n");
  EXPECT_EXIT(
      {
        install_interrupt_handlers();
        std::raise(SIGTERM);
        std::exit(0);
      },
      testing::ExitedWithCode(143), "interrupted by SIGTERM while reading the scene");
}

TEST(InterruptDeathTest, WhileRenderingTheFirstSignalRaisesTheStopFlagAndIsKept) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        install_interrupt_handlers();
        set_interrupt_phase(InterruptPhase::rendering);
        const bool before = stop_requested().load() || interrupting_signal() != 0;
        std::raise(SIGTERM);
        std::raise(SIGINT);
        const bool kept = stop_requested().load() && interrupting_signal() == SIGTERM;
        std::exit(!before && kept ? 42 : 1);
      },
      testing::ExitedWithCode(42), "");
}

TEST(InterruptDeathTest, OnceEndingASignalExitsWithTheCodeGivenAndSaysNothing) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        install_interrupt_handlers();
        set_interrupt_phase(InterruptPhase::rendering);
        end_quietly_on_signal(7);
        std::raise(SIGINT);
        std::exit(0);
      },
      testing::ExitedWithCode(7), "^$");
}

TEST(Interrupt, SignalNamesAndExitCodes) {
  EXPECT_EQ(signal_name(SIGINT), "SIGINT");
  EXPECT_EQ(signal_name(SIGTERM), "SIGTERM");
  EXPECT_EQ(signal_name(SIGHUP), "signal " + std::to_string(SIGHUP));
  EXPECT_EQ(interrupted_exit_code(SIGINT), 130);
  EXPECT_EQ(interrupted_exit_code(SIGTERM), 143);
}

}  // namespace
}  // namespace quiver
