// The C library's heap starts on a huge-page boundary (linked into rayview-cli and rayview-viewer).
//
// The launcher advises every malloc arena onto transparent huge pages (app/launcher.cpp), but the kernel can
// back only whole, aligned 2 MiB ranges of a mapping with a huge page. The heap starts where the kernel put the
// program break, at a random 4 KiB page (address-space randomisation), so its first 0-2 MiB, the memory the
// first allocations get (the scene's text, its arrays), were faulted in 4 KiB at a time: bunny's process took
// 156 of its ~880 page faults there, at ~13 us each on this project's machines (docs/PERFORMANCE.md, "2026-11-24,
// sixth session"). Moving the break up to the next boundary before anything allocates costs address space only:
// the skipped pages are never touched.
#include <unistd.h>

#include <cstdint>

namespace {

constexpr std::uintptr_t kHugePage = std::uintptr_t{2} << 20;

void alignHeapStart(int, char**, char**) {
  void* const end = ::sbrk(0);
  if (end == reinterpret_cast<void*>(-1)) return;
  const auto at = reinterpret_cast<std::uintptr_t>(end);
  const std::uintptr_t skip = (kHugePage - at % kHugePage) % kHugePage;
  // Should malloc already have taken memory from the break, it notices the move and carries on from the new
  // break (glibc treats it as another caller's sbrk); if the break cannot move, the heap stays where it was.
  if (skip != 0) ::sbrk(static_cast<intptr_t>(skip));
}

// .preinit_array: run by the dynamic loader before any library's initialisers, so before the first malloc.
[[maybe_unused]] __attribute__((section(".preinit_array"), used)) void (*const kAlignHeapStart)(int, char**, char**) =
    alignHeapStart;

}  // namespace
