// The signals that would end the process while a file is being written remove its temporary file first.
#include <signal.h>
#include <unistd.h>

#include "rayview/image.h"

namespace rayview {
namespace {

// Every signal whose default action ends the process and that a handler can catch (SIGKILL and SIGSTOP
// cannot be), in one list: the asynchronous ones, which end the process as a shell reports it (128 + signal)...
constexpr int kEndingSignals[] = {SIGHUP,  SIGINT,    SIGQUIT, SIGPIPE, SIGALRM, SIGTERM, SIGUSR1, SIGUSR2,
                                  SIGPOLL, SIGVTALRM, SIGPROF, SIGXCPU, SIGXFSZ, SIGSTKFLT, SIGPWR};
// ...and the ones a fault or abort() raises, which go on to their default action (a core dump) once the file is gone.
constexpr int kFaultSignals[] = {SIGABRT, SIGBUS, SIGFPE, SIGILL, SIGSEGV, SIGSYS, SIGTRAP};

extern "C" void onEndingSignal(int signal) {
  if (const char* temporary = temporaryFileInProgress()) ::unlink(temporary);
  ::_exit(128 + signal);
}

extern "C" void onFaultSignal(int signal) {
  if (const char* temporary = temporaryFileInProgress()) ::unlink(temporary);
  // SA_RESETHAND restored the default action: a fault happens again on return, abort() raises again.
  ::raise(signal);
}

void installWhereDefault(int signal, void (*handler)(int), int flags) {
  struct sigaction current {};
  if (sigaction(signal, nullptr, &current) != 0) return;
  // An ignored signal (nohup's SIGHUP) stays ignored; a handler already there (a sanitizer's) stays.
  if ((current.sa_flags & SA_SIGINFO) != 0 || current.sa_handler != SIG_DFL) return;
  struct sigaction action {};
  action.sa_handler = handler;
  action.sa_flags = flags;
  sigfillset(&action.sa_mask);
  sigaction(signal, &action, nullptr);
}

}  // namespace

void removeTemporaryFileOnSignals() {
  for (int signal : kEndingSignals) installWhereDefault(signal, onEndingSignal, 0);
  for (int signal : kFaultSignals) installWhereDefault(signal, onFaultSignal, SA_RESETHAND | SA_NODEFER);
}

}  // namespace rayview
