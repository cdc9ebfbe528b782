#pragma once
// The viewer being ended from outside: SIGTERM (kill; mpirun ending the whole job because a rank died, which it
// does without --enable-recovery and follows with SIGKILL about a second later), SIGHUP (the terminal closed),
// SIGINT (Ctrl+C in it). The handler only notes the signal and wakes a thread of its own. That thread says on
// stderr at once why the viewer ends and where the unsaved edits are (the note the UI loop keeps up to date: mpirun's
// SIGKILL may follow its SIGTERM within milliseconds), then wakes the UI loop, which writes the latest edits to
// their recovery file and shows the same in the window. If the loop has not ended the process within
// kTerminationGrace, that thread ends it as the signal's default action would (exit 128 + signal), removing a
// temporary file being written first.

#include <chrono>
#include <functional>
#include <string>

namespace rayview {

inline constexpr std::chrono::milliseconds kTerminationGrace{900};

// Installs the handlers and starts the thread, once per process; `wake` (thread-safe) wakes the UI loop.
// `underMpirun`: a SIGTERM is mpirun ending the whole job.
void watchForTermination(std::function<void()> wake, bool underMpirun);
// What the thread says about the unsaved edits if a signal comes now ("your unsaved edits are kept in ...").
void setTerminationNote(std::string note);
// Why the viewer is being ended by `signal`, as said on stderr and in the window.
std::string terminationReason(int signal);
// The signal that asked the viewer to end, or 0.
int terminationSignal();

}  // namespace rayview
