#include "process_memory.h"

#include <cstdio>
#include <cstring>

namespace rayview {

std::uint64_t peakResidentBytes() {
  std::FILE* status = std::fopen("/proc/self/status", "r");
  if (!status) return 0;
  char line[256];
  unsigned long long kib = 0;
  while (std::fgets(line, sizeof line, status))
    if (std::strncmp(line, "VmHWM:", 6) == 0 && std::sscanf(line + 6, "%llu", &kib) == 1) break;
  std::fclose(status);
  return static_cast<std::uint64_t>(kib) * 1024;  // the kernel's "kB" are KiB
}

}  // namespace rayview
