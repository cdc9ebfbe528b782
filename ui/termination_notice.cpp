#include "termination_notice.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>

#include "rayview/image.h"

namespace rayview {
namespace {

std::atomic<int> g_signal{0};
int g_pipe[2] = {-1, -1};
bool g_underMpirun = false;  // set once, before the thread starts
std::mutex g_noteMutex;
std::string g_note = "there were no unsaved edits";

const char* describeTermination(int signal) {
  switch (signal) {
    case SIGTERM: return "SIGTERM";
    case SIGHUP: return "SIGHUP: the terminal closed";
    case SIGINT: return "SIGINT: Ctrl+C";
    default: return "a signal";
  }
}

extern "C" void noteTermination(int signal) {
  int expected = 0;
  g_signal.compare_exchange_strong(expected, signal);
  const int saved = errno;
  const char byte = 1;
  [[maybe_unused]] const ssize_t n = ::write(g_pipe[1], &byte, 1);  // async-signal-safe; full pipe: already woken
  errno = saved;
}

void watch(std::function<void()> wake) {
  char byte = 0;
  while (::read(g_pipe[0], &byte, 1) < 0 && errno == EINTR) {
  }
  std::string note;
  {
    std::lock_guard lock(g_noteMutex);
    note = g_note;
  }
  std::fprintf(stderr, "rayview: %s.\n%s.\n", terminationReason(g_signal.load()).c_str(), note.c_str());
  std::fflush(stderr);
  wake();
  std::this_thread::sleep_for(kTerminationGrace);
  // The loop did not end the process in time (a long save, a stuck driver): end it as the signal would.
  if (const char* temporary = temporaryFileInProgress()) ::unlink(temporary);
  ::_exit(128 + g_signal.load());
}

}  // namespace

void watchForTermination(std::function<void()> wake, bool underMpirun) {
  static std::atomic<bool> started{false};
  if (started.exchange(true)) return;
  g_underMpirun = underMpirun;
  if (::pipe2(g_pipe, O_CLOEXEC | O_NONBLOCK) != 0) return;
  // The reading end blocks; the writing end never does (the handler must not).
  ::fcntl(g_pipe[0], F_SETFL, ::fcntl(g_pipe[0], F_GETFL) & ~O_NONBLOCK);
  std::thread(watch, std::move(wake)).detach();
  struct sigaction action {};
  action.sa_handler = noteTermination;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  for (const int s : {SIGTERM, SIGHUP, SIGINT}) {
    struct sigaction old {};
    // An ignored signal (nohup) stays ignored.
    if (::sigaction(s, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
    ::sigaction(s, &action, nullptr);
  }
}

int terminationSignal() { return g_signal.load(); }

void setTerminationNote(std::string note) {
  std::lock_guard lock(g_noteMutex);
  g_note = std::move(note);
}

std::string terminationReason(int signal) {
  // Under mpirun a SIGTERM is mpirun ending the whole job, which it does when a rank dies (mpirun names the rank).
  if (g_underMpirun && signal == SIGTERM)
    return "mpirun is ending the job (SIGTERM): a rank of it probably died, and without\n"
           "--enable-recovery mpirun ends every rank (its own message names the rank)";
  return std::string("rayview is being ended (") + describeTermination(signal) + ")";
}

}  // namespace rayview
