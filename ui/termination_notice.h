#pragma once
// The viewer being ended from outside: SIGTERM (kill; mpirun ending the whole job because a rank died, which it
// does without --enable-recovery and follows with SIGKILL about a second later), SIGHUP (the terminal closed),
// SIGINT (Ctrl+C in it). The handler only notes the signal and wakes a thread of its own, which wakes the UI loop:
// the loop writes the unsaved edits to their recovery file at once and says in the window and on stderr what
// happened. If the loop has not ended the process within kTerminationGrace, that thread ends it as the signal's
// default action would (exit 128 + signal), removing a temporary file being written first.

#include <chrono>
#include <functional>

namespace rayview {

inline constexpr std::chrono::milliseconds kTerminationGrace{900};

// Installs the handlers and starts the thread, once per process; `wake` (thread-safe) wakes the UI loop.
void watchForTermination(std::function<void()> wake);
// The signal that asked the viewer to end, or 0.
int terminationSignal();
// Its name and what usually sends it ("SIGTERM", "SIGHUP: the terminal closed").
const char* describeTermination(int signal);

}  // namespace rayview
