// Why: the launcher (launcher.cpp) puts every malloc arena on transparent huge pages, which makes a render's page
// faults cheap, but the kernel then backs any touched part of an aligned 2 MiB range with all of it: each hole the
// load or the build frees, and the heap's top, count whole. For a scene of 1e5 triangles that was 2-6 MiB of a limit
// of 19.1 (200 bytes a triangle), against nothing for the scenes the huge pages speed up (docs/PERFORMANCE.md,
// "2026-11-25, thirteenth session"). glibc reads its tunables only when a process starts, before the scene is known;
// the kernel's per-process switch and mallopt() work at any time.
#include "lean_heap.h"

#include <malloc.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <unistd.h>

#include <cstdint>

#include "rayview/lean_memory.h"

namespace rayview {

void useLeanHeap() {
  static bool done = false;
  if (!done) {
    done = true;
    // Faults from here on take 4 KiB pages. Huge pages already in place stay.
    ::prctl(PR_SET_THP_DISABLE, 1, 0, 0, 0);
    // Blocks of 128 KiB or more in their own mappings, given back whole when freed; the heap grown and trimmed by
    // what it needs (the launcher's 16 MiB steps and 256 MiB trim threshold undone).
    ::mallopt(M_MMAP_THRESHOLD, 128 * 1024);
    ::mallopt(M_TOP_PAD, 0);
    ::mallopt(M_TRIM_THRESHOLD, 128 * 1024);
  }
  // The free pages inside the heap, too (glibc's malloc_trim gives those back as well as its top).
  ::malloc_trim(0);
  // But with the launcher's hugetlb tunable glibc trims the heap's top only in whole 2 MiB steps, so up to 2 MiB of
  // free pages at the top stay resident: given back here, past the top chunk's header (the chunk stays the heap's;
  // its pages come back zeroed when next touched).
  const std::size_t top = ::mallinfo2().keepcost;
  const auto end = reinterpret_cast<std::uintptr_t>(::sbrk(0));
  const auto page = static_cast<std::uintptr_t>(::sysconf(_SC_PAGESIZE));
  if (end != static_cast<std::uintptr_t>(-1) && top > 2 * page && end > top) {
    const std::uintptr_t from = (end - top + page + page - 1) & ~(page - 1);
    if (from < end) ::madvise(reinterpret_cast<void*>(from), end - from, MADV_DONTNEED);
  }
}

void useLeanHeapForTheWrite() {
  useLeanHeap();
  ::prctl(PR_SET_THP_DISABLE, 0, 0, 0, 0);
}

void useLeanHeapForEstimate(std::size_t estimatedTriangles) {
  if (isLeanScene(estimatedTriangles)) useLeanHeap();
}

}  // namespace rayview
