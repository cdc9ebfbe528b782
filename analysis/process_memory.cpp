#include "rayview/process_memory.h"

#include <cstdio>
#include <cstring>

namespace rayview {

ProcessMemory processMemory() {
  ProcessMemory memory;
  std::FILE* status = std::fopen("/proc/self/status", "r");
  if (!status) return memory;
  char line[256];
  unsigned long long kib = 0;  // the kernel's "kB" are KiB
  while (std::fgets(line, sizeof line, status)) {
    if (std::strncmp(line, "VmHWM:", 6) == 0 && std::sscanf(line + 6, "%llu", &kib) == 1) memory.peak = kib * 1024;
    if (std::strncmp(line, "VmRSS:", 6) == 0 && std::sscanf(line + 6, "%llu", &kib) == 1) memory.resident = kib * 1024;
  }
  std::fclose(status);
  return memory;
}

}  // namespace rayview
