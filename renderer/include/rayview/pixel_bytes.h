#pragma once
// The bytes of an image: an allocator that leaves value-less construction unwritten and gives big buffers pages of
// their own, advised for huge pages. A fresh process pays for every 4 KiB page it first touches (a fault each,
// 0.3-13 us on the machines measured); a frame rendered whole is written by the threads that render it, not zeroed
// by one thread first, and its faults are one per 2 MiB where the kernel has huge pages to give
// (docs/PERFORMANCE.md, "Fresh pages").

#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <utility>
#include <vector>

namespace rayview {

// Buffers from this size on get a mapping of their own, rounded up to whole huge pages (at most 2 MiB more).
inline constexpr std::size_t kOwnPagesBytes = std::size_t{1} << 20;

// A mapping of at least `bytes` (>= kOwnPagesBytes), aligned to 2 MiB and advised for huge pages (the kernel may
// still give 4 KiB pages). Throws std::bad_alloc.
void* allocateOwnPages(std::size_t bytes);
void freeOwnPages(void* p, std::size_t bytes);

template <class T>
struct PixelAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = PixelAllocator<U>;
  };
  PixelAllocator() = default;
  template <class U>
  PixelAllocator(const PixelAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    if (n >= kOwnPagesBytes / sizeof(T)) {
      if (n > SIZE_MAX / sizeof(T)) throw std::bad_array_new_length();
      return static_cast<T*>(allocateOwnPages(n * sizeof(T)));
    }
    return std::allocator<T>::allocate(n);
  }
  void deallocate(T* p, std::size_t n) noexcept {
    if (n >= kOwnPagesBytes / sizeof(T)) return freeOwnPages(p, n * sizeof(T));
    std::allocator<T>::deallocate(p, n);
  }
  template <class U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;  // default-initialised: a byte is left as it is
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};
template <class T, class U>
bool operator==(const PixelAllocator<T>&, const PixelAllocator<U>&) noexcept {
  return true;
}

using PixelBytes = std::vector<std::uint8_t, PixelAllocator<std::uint8_t>>;

}  // namespace rayview
