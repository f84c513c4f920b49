#include "app/stage_status.h"

#include <algorithm>
#include <string>
#include <utility>

#include "app/interrupt.h"

namespace quiver {

StageStatus::StageStatus(std::FILE* out, ProgressStyle style, Clock::duration delay, Clock::duration interval)
    : out_(out), delay_(delay), interval_(interval) {
  if (out_ == nullptr || style != ProgressStyle::terminal) {
    ended_ = true;
    return;
  }
  thread_ = std::thread([this] { run(); });
}

StageStatus::StageStatus(std::FILE* out, ProgressStyle style)
    : StageStatus(out, style, std::chrono::seconds(1), std::chrono::milliseconds(200)) {}

StageStatus::~StageStatus() { end(); }

void StageStatus::begin(std::string step) {
  std::lock_guard lock(mutex_);
  if (ended_) return;
  step_ = std::move(step);
  step_start_ = Clock::now();
}

void StageStatus::end() {
  {
    std::lock_guard lock(mutex_);
    if (ended_ && !thread_.joinable()) return;
    ended_ = true;
    if (shown_width_ > 0) {
      // Blanks over the line, then back to its start.
      std::fprintf(out_, "\r%s\r", std::string(shown_width_, ' ').c_str());
      std::fflush(out_);
      shown_width_ = 0;
      note_status_line(false);
    }
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void StageStatus::run() {
  std::unique_lock lock(mutex_);
  while (!ended_) {
    wake_.wait_for(lock, interval_, [this] { return ended_; });
    if (!ended_ && !step_.empty() && Clock::now() - step_start_ >= delay_) draw_locked();
  }
}

void StageStatus::draw_locked() {
  const double seconds = std::chrono::duration<double>(Clock::now() - step_start_).count();
  char time[32];
  std::snprintf(time, sizeof time, ": %.1f s", seconds);
  std::string line = step_ + time;
  // Blanks clear what a longer earlier line left.
  const std::size_t width = line.size();
  if (width < shown_width_) line.append(shown_width_ - width, ' ');
  std::fprintf(out_, "\r%s", line.c_str());
  std::fflush(out_);
  shown_width_ = std::max(shown_width_, width);
  note_status_line(true);
}

}  // namespace quiver
