#include "rayview/own_pages.h"

#include <mutex>
#include <utility>

#include <sys/mman.h>

namespace rayview {
namespace {

constexpr std::size_t kSmallPage = 4096;

std::size_t roundedTo(std::size_t bytes, std::size_t unit) { return (bytes + unit - 1) / unit * unit; }

// The length of the mapping made for `bytes`.
std::size_t mappedBytes(std::size_t bytes, OwnPages kind) {
  if (kind == OwnPages::Exact && bytes > kHugePageBytes) return roundedTo(bytes, kSmallPage);
  return roundedTo(bytes, kHugePageBytes);
}

// The last RoundedUp mapping freed, kept for the next request of its size: a viewer's per-pass copies of a frame
// (display mapping, differences) reuse pages already touched, as the heap's reuse would give them, instead of a
// fresh mapping's faults every pass.
struct KeptMapping {
  std::mutex mutex;
  void* pages = nullptr;
  std::size_t size = 0;
};
KeptMapping& kept() {
  static KeptMapping* const mapping = new KeptMapping;  // never destroyed: frees may come during exit
  return *mapping;
}

}  // namespace

void* allocateOwnPages(std::size_t bytes, OwnPages kind) {
  if (bytes > SIZE_MAX - 2 * kHugePageBytes) throw std::bad_alloc();
  const std::size_t size = mappedBytes(bytes, kind);
  if (kind == OwnPages::RoundedUp) {
    KeptMapping& k = kept();
    const std::lock_guard lock(k.mutex);
    if (k.pages && k.size == size) return std::exchange(k.pages, nullptr);
  }
  // Mapped a huge page longer than needed, then trimmed to a 2 MiB-aligned start: mmap itself aligns to 4 KiB only.
  void* mapped = ::mmap(nullptr, size + kHugePageBytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (mapped == MAP_FAILED) throw std::bad_alloc();
  const auto start = reinterpret_cast<std::uintptr_t>(mapped);
  const std::uintptr_t aligned = roundedTo(start, kHugePageBytes);
  if (aligned > start) ::munmap(mapped, aligned - start);
  const std::uintptr_t tail = aligned + size, end = start + size + kHugePageBytes;
  if (end > tail) ::munmap(reinterpret_cast<void*>(tail), end - tail);
  const std::size_t advised = kind == OwnPages::RoundedUp ? size : size / kHugePageBytes * kHugePageBytes;
  if (advised > 0) ::madvise(reinterpret_cast<void*>(aligned), advised, MADV_HUGEPAGE);
  return reinterpret_cast<void*>(aligned);
}

void freeOwnPages(void* p, std::size_t bytes, OwnPages kind) noexcept {
  void* released = p;
  std::size_t releasedSize = mappedBytes(bytes, kind);
  if (kind == OwnPages::RoundedUp) {
    KeptMapping& k = kept();
    const std::lock_guard lock(k.mutex);
    std::swap(released, k.pages);  // this one is kept; the one kept before, if any, goes back
    std::swap(releasedSize, k.size);
  }
  if (released) ::munmap(released, releasedSize);
}

}  // namespace rayview
