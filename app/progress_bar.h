// Progress of `quiver render` and quiver-mpi's rank 0: tiles done of total,
// percent, elapsed seconds and an estimate of the time left. On a terminal
// a bar redrawn in place with '\r' (at most once per `interval`, finish()
// ending it with a newline); elsewhere (a log, a batch job) one line per
// `interval`. Either stays silent for short renders (nothing before
// `delay`). Calls must not overlap (render() serialises its progress
// callback).
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdio>
#include <optional>

namespace quiver {

enum class ProgressStyle { off, terminal, log };

// The style for stderr: off under --quiet, the bar on a terminal, lines
// otherwise.
ProgressStyle progress_style_for(std::FILE* out, bool quiet);

// Seconds left if the remaining work goes at the pace of the work done
// (shares of the whole, 0 to 1): elapsed * (1 - done) / done. None before
// any work is done.
std::optional<double> seconds_left(double work_done, double elapsed_seconds);

class ProgressBar {
 public:
  using Clock = std::chrono::steady_clock;

  // A log gets a line every 5 s, the first after 5 s, unless told otherwise.
  ProgressBar(std::FILE* out, ProgressStyle style, Clock::duration delay, Clock::duration interval);
  ProgressBar(std::FILE* out, ProgressStyle style);

  // work_done: the share of the work done (0 to 1), behind the time left;
  // work_seconds: the time that work took, when the elapsed time holds more
  // (the setup before the first tile is no part of the work's pace).
  void update(std::size_t done, std::size_t total, double work_done,
              std::optional<double> work_seconds = std::nullopt);
  // The bar: draws the final state if it is showing, then a newline. A log:
  // nothing (the render's summary line follows).
  void finish();

  bool drawn() const { return drawn_; }

 private:
  void draw(Clock::time_point now);

  std::FILE* out_;
  ProgressStyle style_;
  Clock::duration delay_, interval_;
  Clock::time_point start_, last_draw_;
  std::size_t done_ = 0, total_ = 0;
  double work_done_ = 0.0;
  std::optional<double> work_seconds_;
  bool drawn_ = false, finished_ = false;
};

// True when the file is a terminal (isatty).
bool is_terminal(std::FILE* file);

}  // namespace quiver
