// A status line for the steps before a render that can take seconds (reading
// and building a large scene): on a terminal, "reading scene.ply: 2.4 s"
// redrawn in place from a thread of its own, shown once a step has run for
// `delay` and erased when the steps end, so the progress bar or the
// messages that follow start on a clean line (a signal's message while the
// line is shown starts on a line of its own: app/interrupt.h). Silent
// elsewhere (a log gets the load and build times in the render's summary
// line).
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>

#include "app/progress_bar.h"

namespace quiver {

class StageStatus {
 public:
  using Clock = std::chrono::steady_clock;

  StageStatus(std::FILE* out, ProgressStyle style, Clock::duration delay, Clock::duration interval);
  // A second's delay, redrawn five times a second.
  StageStatus(std::FILE* out, ProgressStyle style);
  ~StageStatus();
  StageStatus(const StageStatus&) = delete;
  StageStatus& operator=(const StageStatus&) = delete;

  // A new step (its time counted from now), replacing the one before.
  void begin(std::string step);
  // Erases the line (if shown) and stops; nothing is drawn afterwards.
  void end();

 private:
  void run();
  void draw_locked();

  std::FILE* out_;
  Clock::duration delay_, interval_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::string step_;
  Clock::time_point step_start_;
  std::size_t shown_width_ = 0;  // characters on the line now; 0: nothing shown
  bool ended_ = false;
  std::thread thread_;
};

}  // namespace quiver
