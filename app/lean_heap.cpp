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

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <utility>

#include "rayview/lean_memory.h"

namespace rayview {
namespace {

// The program break's memory, from /proc/self/maps: the [heap] mappings, which advice to parts of it (huge pages or
// not) splits into several, one after another; {0, 0} if there is none or they are not one range.
std::pair<std::uintptr_t, std::uintptr_t> heapRange() {
  std::FILE* maps = std::fopen("/proc/self/maps", "r");
  if (!maps) return {0, 0};
  char line[512];
  std::pair<std::uintptr_t, std::uintptr_t> range{0, 0};
  bool broken = false;
  while (std::fgets(line, sizeof line, maps)) {
    if (!std::strstr(line, "[heap]")) continue;
    unsigned long begin = 0, end = 0;
    if (std::sscanf(line, "%lx-%lx", &begin, &end) != 2) broken = true;
    else if (range.second == 0) range = {begin, end};
    else if (begin == range.second) range.second = end;
    else broken = true;
  }
  std::fclose(maps);
  return broken ? std::pair<std::uintptr_t, std::uintptr_t>{0, 0} : range;
}

// The pages of malloc's top chunk (the free space at the end of the main arena, `keepcost` bytes ending at the
// program break) given back to the kernel, past the chunk's header: the chunk stays malloc's, and its pages come
// back zeroed when next touched, which malloc allows for free memory. Only when it is certain where the chunk is:
// the arena ends at the break inside the [heap] mappings, and the word where glibc keeps the chunk's size holds that
// size. Otherwise (a main arena that had to continue elsewhere, another allocator, the break just moved by a trim
// in progress) nothing is done.
void releaseTopChunkPages() {
  // The mappings first: reading them allocates (stdio's FILE and buffer), which may take from the top chunk.
  const auto [heapBegin, heapEnd] = heapRange();
  const std::size_t top = ::mallinfo2().keepcost;
  const auto page = static_cast<std::uintptr_t>(::sysconf(_SC_PAGESIZE));
  const auto end = reinterpret_cast<std::uintptr_t>(::sbrk(0));
  if (top <= 2 * page || end == static_cast<std::uintptr_t>(-1) || end < top) return;
  const std::uintptr_t chunk = end - top;
  if (chunk < heapBegin || end > heapEnd || chunk % alignof(std::max_align_t) != 0) return;
  std::size_t sizeField = 0;
  std::memcpy(&sizeField, reinterpret_cast<const void*>(chunk + sizeof(std::size_t)), sizeof sizeField);
  if ((sizeField & ~std::size_t{7}) != top) return;
  const std::uintptr_t from = (chunk + page + page - 1) & ~(page - 1);
  if (from < end) ::madvise(reinterpret_cast<void*>(from), end - from, MADV_DONTNEED);
}

}  // namespace

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
  // free pages at the top stay resident (2.2 MB for the 1e5 sphere): given back here.
  releaseTopChunkPages();
}

void useLeanHeapForTheWrite() {
  useLeanHeap();
  ::prctl(PR_SET_THP_DISABLE, 0, 0, 0, 0);
}

void useLeanHeapForEstimate(std::size_t estimatedTriangles) {
  if (isLeanScene(estimatedTriangles)) useLeanHeap();
}

}  // namespace rayview
