// What a first touch of fresh memory costs on this machine (docs/PERFORMANCE.md, "Current figures"):
// a figure to judge a huge-page choice by: what a render pays per page it touches.
//
// For each way of getting memory, maps a fresh anonymous region of --megabytes (2 MiB-aligned), touches one
// byte per 4 KiB page and reports the time per 4 KiB page (median of --repeat):
//   4 KiB pages      one page fault per page, as malloc'd memory is by default;
//   huge pages       madvise(MADV_HUGEPAGE) first (what glibc.malloc.hugetlb=1 does to malloc's memory);
//   populated        madvise(MADV_POPULATE_WRITE) first: every page in one call, no fault per page.
//
//     build/release/bench/page_fault_bench [--megabytes 64] [--repeat 5]
#include <sys/mman.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#ifndef MADV_POPULATE_WRITE
#define MADV_POPULATE_WRITE 23  // Linux 5.14
#endif

namespace {

constexpr std::size_t kPage = 4096, kHugePage = std::size_t{2} << 20;

double touchMs(std::size_t bytes, int advice) {
  const auto start = std::chrono::steady_clock::now();
  void* mapped = mmap(nullptr, bytes + kHugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (mapped == MAP_FAILED) {
    std::perror("page_fault_bench: mmap");
    std::exit(1);
  }
  auto* region = reinterpret_cast<volatile char*>(
      (reinterpret_cast<std::uintptr_t>(mapped) + kHugePage - 1) & ~(kHugePage - 1));
  if (advice >= 0 && madvise(const_cast<char*>(region), bytes, advice) != 0) std::perror("page_fault_bench: madvise");
  for (std::size_t at = 0; at < bytes; at += kPage) region[at] = 1;
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  munmap(mapped, bytes + kHugePage);
  return ms;
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t megabytes = 64;
  int repeat = 5;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--megabytes")) megabytes = std::strtoul(argv[i + 1], nullptr, 10);
    else if (!std::strcmp(argv[i], "--repeat")) repeat = std::atoi(argv[i + 1]);
  }
  megabytes = std::max<std::size_t>(2, megabytes & ~std::size_t{1});
  const std::size_t bytes = megabytes << 20;
  std::printf("| memory | us per 4 KiB page | ms for %zu MiB |\n|---|---:|---:|\n", megabytes);
  const struct {
    const char* name;
    int advice;
  } ways[] = {{"4 KiB pages (a fault per page)", -1}, {"huge pages (MADV_HUGEPAGE)", MADV_HUGEPAGE},
              {"populated in one call (MADV_POPULATE_WRITE)", MADV_POPULATE_WRITE}};
  for (const auto& way : ways) {
    std::vector<double> ms;
    for (int r = 0; r < std::max(1, repeat); ++r) ms.push_back(touchMs(bytes, way.advice));
    std::sort(ms.begin(), ms.end());
    const double median = ms[ms.size() / 2];
    std::printf("| %s | %.2f | %.1f |\n", way.name, 1000.0 * median / static_cast<double>(bytes / kPage), median);
  }
}
