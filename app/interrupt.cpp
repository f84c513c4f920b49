#include "app/interrupt.h"

#include <signal.h>
#include <unistd.h>

#include <csignal>
#include <cstring>

namespace quiver {

namespace {

std::atomic<bool> stop_flag{false};
std::atomic<int> stop_signal{0};
std::atomic<InterruptPhase> phase{InterruptPhase::reading};
std::atomic<int> ending_exit_code{0};
std::atomic<bool> status_line{false};
static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<int>::is_always_lock_free &&
                  std::atomic<InterruptPhase>::is_always_lock_free,
              "signal handlers may touch only lock-free atomics");

// Only async-signal-safe calls: atomics, write, _exit.
void on_signal(int signal) {
  if (phase.load() == InterruptPhase::ending) ::_exit(ending_exit_code.load());
  if (phase.load() == InterruptPhase::reading) {
    if (status_line.load()) {
      [[maybe_unused]] const ssize_t ended = ::write(STDERR_FILENO, "\n", 1);
    }
    const char* message = signal == SIGINT ? "quiver: interrupted by SIGINT while reading the scene; nothing written\n"
                                           : "quiver: interrupted by SIGTERM while reading the scene; nothing written\n";
    [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, message, std::strlen(message));
    ::_exit(interrupted_exit_code(signal));
  }
  int none = 0;
  stop_signal.compare_exchange_strong(none, signal);
  stop_flag.store(true);
}

}  // namespace

void install_interrupt_handlers() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  ::sigaction(SIGINT, &action, nullptr);
  ::sigaction(SIGTERM, &action, nullptr);
}

void set_interrupt_phase(InterruptPhase next) { phase.store(next); }

void note_status_line(bool shown) { status_line.store(shown); }
bool status_line_shown() { return status_line.load(); }

void end_quietly_on_signal(int exit_code) {
  ending_exit_code.store(exit_code);
  phase.store(InterruptPhase::ending);
}

const std::atomic<bool>& stop_requested() { return stop_flag; }

int interrupting_signal() { return stop_signal.load(); }

std::string signal_name(int signal) {
  if (signal == SIGINT) return "SIGINT";
  if (signal == SIGTERM) return "SIGTERM";
  return "signal " + std::to_string(signal);
}

}  // namespace quiver
