#include "app/progress_bar.h"

#include <unistd.h>

#include <string>

namespace quiver {

namespace {
constexpr int kBarWidth = 30;
}

ProgressBar::ProgressBar(std::FILE* out, bool enabled, Clock::duration delay, Clock::duration interval)
    : out_(out), enabled_(enabled && out != nullptr), delay_(delay), interval_(interval), start_(Clock::now()) {}

void ProgressBar::update(std::size_t done, std::size_t total) {
  done_ = done;
  total_ = total;
  if (!enabled_ || finished_) return;
  const Clock::time_point now = Clock::now();
  if (now - start_ < delay_) return;
  if (drawn_ && now - last_draw_ < interval_) return;
  draw(done, total, now);
}

void ProgressBar::finish() {
  if (!enabled_ || finished_) return;
  finished_ = true;
  if (!drawn_) return;
  draw(done_, total_, Clock::now());
  std::fputc('\n', out_);
  std::fflush(out_);
}

void ProgressBar::draw(std::size_t done, std::size_t total, Clock::time_point now) {
  const double fraction = total == 0 ? 1.0 : double(done) / double(total);
  const int filled = static_cast<int>(fraction * kBarWidth);
  std::string bar(std::size_t(kBarWidth), ' ');
  for (int i = 0; i < filled && i < kBarWidth; ++i) bar[std::size_t(i)] = '#';
  const double seconds = std::chrono::duration<double>(now - start_).count();
  std::fprintf(out_, "\r[%s] %3d%%  %zu/%zu tiles  %.1f s", bar.c_str(), static_cast<int>(fraction * 100.0), done,
               total, seconds);
  std::fflush(out_);
  drawn_ = true;
  last_draw_ = now;
}

bool is_terminal(std::FILE* file) { return file != nullptr && ::isatty(::fileno(file)) == 1; }

}  // namespace quiver
