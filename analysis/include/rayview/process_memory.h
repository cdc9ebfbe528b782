#pragma once
// This process's resident memory now and at its peak, from the kernel (VmRSS and VmHWM in /proc/self/status):
// `rayview render`'s memory line (peak memory in bytes per triangle, the figure memory is judged by), the viewer's
// stats and the scale series' breakdown (bench/scale_series.cpp). The peak is the figure bench/peak_rss takes from
// outside (ru_maxrss), but readable between the stages of one process. A reading costs ~20 us (docs/PERFORMANCE.md,
// "Current figures").
//
// Approximate by up to a few hundred KiB while threads run: the kernel counts each thread's page faults in that
// thread's cache first and adds them to the process's figure in batches, so two readings of the peak can even
// come in falling order (seen: 31.9 then 31.6 MiB). A caller reporting stages takes the running maximum.
#include <cstdint>

namespace rayview {

struct ProcessMemory {
  std::uint64_t resident = 0;  // bytes; 0 where the kernel does not say (no /proc)
  std::uint64_t peak = 0;      // bytes, the high-water mark since the process started (or since it was reset)
};

ProcessMemory processMemory();

}  // namespace rayview
