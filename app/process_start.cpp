#include "process_start.h"

#include <time.h>

#include <cerrno>
#include <cstdlib>

namespace rayview {
namespace {

long long startNs = 0;
bool fromLaunch = false;

}  // namespace

long long monotonicNanoseconds() {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  return static_cast<long long>(now.tv_sec) * 1'000'000'000LL + now.tv_nsec;
}

void captureProcessStart() {
  const long long now = monotonicNanoseconds();
  startNs = now;
  fromLaunch = false;
  if (const char* text = std::getenv(kLaunchStampVariable)) {
    char* end = nullptr;
    errno = 0;
    const long long stamp = std::strtoll(text, &end, 10);
    constexpr long long kMinute = 60'000'000'000LL;
    if (errno == 0 && end != text && *end == '\0' && stamp <= now && now - stamp < kMinute) {
      startNs = stamp;
      fromLaunch = true;
    }
    ::unsetenv(kLaunchStampVariable);
  }
}

double msSinceProcessStart() { return static_cast<double>(monotonicNanoseconds() - startNs) / 1e6; }

bool processStartIsLaunch() { return fromLaunch; }

}  // namespace rayview
