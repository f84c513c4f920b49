// SIGINT and SIGTERM in `quiver render`. While the scene is read and built
// nothing has been written, so a signal ends the process at once: one line
// on stderr, exit 128 + the signal number (130, 143). From the render on, a
// signal only raises the stop flag: the render stops before its next tile,
// and the caller removes its temporary files, says what was interrupted and
// exits with the same code.
#pragma once

#include <atomic>
#include <string>

namespace quiver {

// ending: the outcome is decided and reported (see end_quietly_on_signal).
enum class InterruptPhase { reading, rendering, ending };

// Installs the handlers (system calls restart after them), the phase being
// `reading`. Idempotent.
void install_interrupt_handlers();

void set_interrupt_phase(InterruptPhase phase);

// Enters the `ending` phase: a signal from now on (mpirun ending the job
// after a rank failed) ends the process at once with exit_code and prints
// nothing, so the error already reported stays the only line.
void end_quietly_on_signal(int exit_code);

// Whether a status line (app/stage_status.h) is on the terminal now: a
// signal while reading then starts its message on a line of its own.
void note_status_line(bool shown);
bool status_line_shown();

// Raised by the first SIGINT or SIGTERM while `rendering`.
const std::atomic<bool>& stop_requested();

// The signal that raised the stop flag; 0 when none did.
int interrupting_signal();

// "SIGINT", "SIGTERM", else "signal N".
std::string signal_name(int signal);

// 128 + signal: the shell's convention for a process ended by a signal.
constexpr int interrupted_exit_code(int signal) { return 128 + signal; }

}  // namespace quiver
