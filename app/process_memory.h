#pragma once
// The process's peak resident memory, for the memory line of `rayview render`'s summary (issue 8 item 4 measures
// peak memory in bytes per triangle). Read from the kernel's high-water mark of this process's resident set
// (VmHWM in /proc/self/status): the same figure bench/peak_rss takes from the outside (ru_maxrss), but readable
// between the stages, so the summary says which stage set the peak.
#include <cstdint>

namespace rayview {

// The peak resident set of this process so far, in bytes; 0 where the kernel does not say (no /proc).
// Approximate by up to a few hundred KiB while threads run: the kernel counts each thread's page faults in
// that thread's cache first, adding them to the process's figure in batches, so two readings can even come in
// falling order (seen: 31.9 then 31.6 MiB). A caller reporting stages takes the running maximum.
std::uint64_t peakResidentBytes();

}  // namespace rayview
