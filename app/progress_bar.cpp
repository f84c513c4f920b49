#include "app/progress_bar.h"

#include <unistd.h>

#include <algorithm>
#include <string>

namespace quiver {

namespace {
constexpr int kBarWidth = 30;
}

ProgressStyle progress_style_for(std::FILE* out, bool quiet) {
  if (quiet || out == nullptr) return ProgressStyle::off;
  return is_terminal(out) ? ProgressStyle::terminal : ProgressStyle::log;
}

std::optional<double> seconds_left(double work_done, double elapsed_seconds) {
  if (!(work_done > 0.0)) return std::nullopt;
  return elapsed_seconds * std::max(1.0 - work_done, 0.0) / work_done;
}

ProgressBar::ProgressBar(std::FILE* out, ProgressStyle style, Clock::duration delay, Clock::duration interval)
    : out_(out),
      style_(out == nullptr ? ProgressStyle::off : style),
      delay_(delay),
      interval_(interval),
      start_(Clock::now()) {}

ProgressBar::ProgressBar(std::FILE* out, ProgressStyle style)
    : ProgressBar(out, style, style == ProgressStyle::log ? Clock::duration(std::chrono::seconds(5))
                                                          : Clock::duration(std::chrono::milliseconds(500)),
                  style == ProgressStyle::log ? Clock::duration(std::chrono::seconds(5))
                                              : Clock::duration(std::chrono::milliseconds(100))) {}

void ProgressBar::update(std::size_t done, std::size_t total, double work_done,
                         std::optional<double> work_seconds) {
  done_ = done;
  total_ = total;
  work_done_ = work_done;
  work_seconds_ = work_seconds;
  if (style_ == ProgressStyle::off || finished_) return;
  const Clock::time_point now = Clock::now();
  if (now - start_ < delay_) return;
  if (drawn_ && now - last_draw_ < interval_) return;
  draw(now);
}

void ProgressBar::finish() {
  if (style_ == ProgressStyle::off || finished_) return;
  finished_ = true;
  if (!drawn_ || style_ == ProgressStyle::log) return;
  draw(Clock::now());
  std::fputc('\n', out_);
  std::fflush(out_);
}

void ProgressBar::draw(Clock::time_point now) {
  const std::size_t done = done_, total = total_;
  const double fraction = total == 0 ? 1.0 : double(done) / double(total);
  const double seconds = std::chrono::duration<double>(now - start_).count();
  const std::optional<double> left = seconds_left(work_done_, std::min(work_seconds_.value_or(seconds), seconds));
  std::string eta;
  if (left && done < total) {
    // Two significant digits below 10 s, so the last seconds read as precisely as the first.
    char text[32];
    std::snprintf(text, sizeof text, *left < 1.0 ? ", ETA %.2f s" : *left < 10.0 ? ", ETA %.1f s" : ", ETA %.0f s",
                  *left);
    eta = text;
  }
  const int percent = static_cast<int>(fraction * 100.0);
  if (style_ == ProgressStyle::log) {
    std::fprintf(out_, "quiver: %d%%, %zu/%zu tiles, %.1f s%s\n", percent, done, total, seconds, eta.c_str());
  } else {
    const int filled = static_cast<int>(fraction * kBarWidth);
    std::string bar(std::size_t(kBarWidth), ' ');
    for (int i = 0; i < filled && i < kBarWidth; ++i) bar[std::size_t(i)] = '#';
    // Trailing blanks clear what a longer previous line left.
    std::fprintf(out_, "\r[%s] %3d%%  %zu/%zu tiles  %.1f s%s    ", bar.c_str(), percent, done, total, seconds,
                 eta.c_str());
  }
  std::fflush(out_);
  drawn_ = true;
  last_draw_ = now;
}

bool is_terminal(std::FILE* file) { return file != nullptr && ::isatty(::fileno(file)) == 1; }

}  // namespace quiver
