// peak_rss COMMAND [ARGS...]: runs COMMAND and prints its peak resident memory ("peak_rss_kb N") on stderr, with
// COMMAND's exit status as its own.
//
// Why not Python's os.fork + os.wait4: Linux keeps a process's ru_maxrss across exec, so a child forked from a
// Python interpreter starts with the interpreter's ~10-13 MB as its peak (`rayview --version` measured that way
// said 9.6 MB; from this program, 3.3 MB). This program is small when it forks: its own ~1 MB is the floor.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: peak_rss COMMAND [ARGS...]\n");
    return 2;
  }
  const pid_t pid = ::fork();
  if (pid < 0) {
    std::perror("peak_rss: fork");
    return 2;
  }
  if (pid == 0) {
    ::execvp(argv[1], argv + 1);
    std::perror("peak_rss: exec");
    _exit(127);
  }
  int status = 0;
  rusage usage{};
  if (::wait4(pid, &status, 0, &usage) < 0) {
    std::perror("peak_rss: wait4");
    return 2;
  }
  std::fprintf(stderr, "peak_rss_kb %ld\n", usage.ru_maxrss);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}
