// `rayview`: sets the C library's allocator up for rendering, then becomes `rayview-cli` (exec: same process,
// arguments and streams), which runs the command, or becomes `rayview-viewer` for the viewer.
//
// Why a launcher: glibc reads its malloc tunables (GLIBC_TUNABLES) only when a process starts, before any
// library is loaded, so the process that renders must be started with them. Measured on this project's
// machines (docs/PERFORMANCE.md, "Page faults and start-up"; bench/page_fault_bench): a first touch of a
// 4 KiB page costs ~12 us there, a few us or less per 4 KiB on a transparent huge page, and a render touches
// thousands of pages (the scene file's text, the arrays, Embree's BVH, the image, the PNG's rows). With these
// settings every malloc arena is advised onto huge pages (hugetlb=1), grows 16 MiB at a time (top_pad), and
// keeps what is freed for reuse instead of giving it back (trim_threshold, mmap_threshold): killeroo_2020's
// whole process ~195 -> ~133 ms (bench/stage_times.py). All threads share the one arena (arena_max=1): on huge pages
// every thread's own arena held 2-6 MB for the few allocations a render or deflate thread makes (at 1e5 triangles
// four of them, 14 MB), and no render was slower for it (docs/PERFORMANCE.md, "2026-11-25, ninth session").
//
// The launcher is a static executable with no libraries to load: it adds about a millisecond.
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "process_start.h"
#include "program_exec.h"

namespace {

constexpr char kTunables[] =
    "glibc.malloc.hugetlb=1:glibc.malloc.top_pad=16777216:glibc.malloc.mmap_threshold=33554432:"
    "glibc.malloc.trim_threshold=268435456:glibc.malloc.arena_max=1";

}  // namespace

int main(int, char** argv) {
  // Settings the user gave come after ours, so theirs win (glibc applies them in order); an implausibly long
  // value of theirs is passed on alone.
  const char* user = std::getenv("GLIBC_TUNABLES");
  if (!user || !*user) {
    ::setenv("GLIBC_TUNABLES", kTunables, 1);
  } else if (std::strlen(user) < 4096) {
    char combined[sizeof kTunables + 4096 + 1];
    std::snprintf(combined, sizeof combined, "%s:%s", kTunables, user);
    ::setenv("GLIBC_TUNABLES", combined, 1);
  }
  // The process starts here: `rayview render` reports its start-up from this moment (process_start.h).
  char stamp[32];
  std::snprintf(stamp, sizeof stamp, "%lld", rayview::monotonicNanoseconds());
  ::setenv(rayview::kLaunchStampVariable, stamp, 1);
  rayview::execSiblingProgram("rayview-cli", argv);
  std::fprintf(stderr, "rayview: error: cannot start rayview-cli beside this executable: %s\n", std::strerror(errno));
  return 126;  // as a shell reports a command it found but could not run
}
