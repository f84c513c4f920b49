// A one-line progress bar for `quiver render` (tiles done of total, percent,
// elapsed seconds), redrawn in place with '\r'. It stays silent for short
// renders (nothing before `delay`), redraws at most once per `interval`, and
// finish() completes the line with a newline if anything was drawn. Calls
// must not overlap (render() serialises its progress callback).
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdio>

namespace quiver {

class ProgressBar {
 public:
  using Clock = std::chrono::steady_clock;

  // enabled = false draws nothing (not a terminal, or --quiet).
  ProgressBar(std::FILE* out, bool enabled, Clock::duration delay = std::chrono::milliseconds(500),
              Clock::duration interval = std::chrono::milliseconds(100));

  void update(std::size_t done, std::size_t total);
  // Draws the final state if the bar is showing, then a newline.
  void finish();

  bool drawn() const { return drawn_; }

 private:
  void draw(std::size_t done, std::size_t total, Clock::time_point now);

  std::FILE* out_;
  bool enabled_;
  Clock::duration delay_, interval_;
  Clock::time_point start_, last_draw_;
  std::size_t done_ = 0, total_ = 0;
  bool drawn_ = false, finished_ = false;
};

// True when the file is a terminal (isatty).
bool is_terminal(std::FILE* file);

}  // namespace quiver
