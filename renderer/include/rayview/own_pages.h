#pragma once
// Big arrays on pages of their own, advised for huge pages. A fresh process pays for every 4 KiB page it first touches
// (a fault each, 11-13 us on the VMs measured here); in a 2 MiB huge page it pays once for 512 of them
// (docs/PERFORMANCE.md, "Fresh pages"). The advice is only advice: where the kernel has no huge page to give, or
// THP is off, the pages are 4 KiB ones, as from malloc.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace rayview {

inline constexpr std::size_t kHugePageBytes = std::size_t{1} << 21;

// From this size on an array gets pages of its own. A quarter of a huge page: its 128 faults cost more than zeroing
// one huge page even where a fault is cheapest (bare metal, ~0.5 us), and 1.4 ms on these VMs against 0.1 ms.
inline constexpr std::size_t kOwnPagesMinBytes = kHugePageBytes / 4;

// How a mapping of its own is advised. Exact: only the whole huge pages inside it, so that past one huge page the
// process never holds more than it asked for (the scene's arrays and the BVH's, whose bytes per triangle are a
// promise); one under a huge page takes a whole one, a fixed cost whatever the scene's size. RoundedUp: up to the next
// whole huge page, at most 2 MiB more, and the last one freed is kept for the next of its size (a frame's pixels, which
// a viewer copies every pass; the loader's read buffers, one after the other).
enum class OwnPages { Exact, RoundedUp };

// A 2 MiB-aligned mapping of at least `bytes`. Throws std::bad_alloc.
void* allocateOwnPages(std::size_t bytes, OwnPages kind);
void freeOwnPages(void* p, std::size_t bytes, OwnPages kind) noexcept;

// std::allocator, except that arrays of at least `MinBytes` are mappings of their own.
template <class T, OwnPages Kind = OwnPages::Exact, std::size_t MinBytes = kOwnPagesMinBytes>
struct OwnPagesAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = OwnPagesAllocator<U, Kind, MinBytes>;
  };
  OwnPagesAllocator() = default;
  template <class U>
  OwnPagesAllocator(const OwnPagesAllocator<U, Kind, MinBytes>&) noexcept {}

  static bool ownPages(std::size_t n) { return n >= MinBytes / sizeof(T); }
  T* allocate(std::size_t n) {
    if (!ownPages(n)) return std::allocator<T>::allocate(n);
    if (n > SIZE_MAX / sizeof(T)) throw std::bad_array_new_length();
    return static_cast<T*>(allocateOwnPages(n * sizeof(T), Kind));
  }
  void deallocate(T* p, std::size_t n) noexcept {
    if (ownPages(n)) return freeOwnPages(p, n * sizeof(T), Kind);
    std::allocator<T>::deallocate(p, n);
  }
};
template <class T, class U, OwnPages Kind, std::size_t MinBytes>
bool operator==(const OwnPagesAllocator<T, Kind, MinBytes>&, const OwnPagesAllocator<U, Kind, MinBytes>&) noexcept {
  return true;
}

// `size` objects of T, left as the allocation gives them (T writes nothing when constructed), from
// OwnPagesAllocator<T, Kind> and given back to it: a buffer that its user fills (the loader's pieces, the PNG
// writer's scratch, the packet BVH's block). Empty when default-constructed; moved, never copied.
template <class T, OwnPages Kind = OwnPages::Exact>
class OwnPagesArray {
  static_assert(std::is_trivially_default_constructible_v<T> && std::is_trivially_destructible_v<T>);
  using Allocator = OwnPagesAllocator<T, Kind>;

 public:
  OwnPagesArray() = default;
  explicit OwnPagesArray(std::size_t size) : size_(size), data_(Allocator().allocate(size)) {
    for (std::size_t k = 0; k < size; ++k) ::new (static_cast<void*>(data_ + k)) T;  // writes nothing
  }
  OwnPagesArray(OwnPagesArray&& other) noexcept
      : size_(std::exchange(other.size_, 0)), data_(std::exchange(other.data_, nullptr)) {}
  OwnPagesArray& operator=(OwnPagesArray&& other) noexcept {
    OwnPagesArray gone(std::move(*this));
    size_ = std::exchange(other.size_, 0);
    data_ = std::exchange(other.data_, nullptr);
    return *this;
  }
  ~OwnPagesArray() {
    if (data_) Allocator().deallocate(data_, size_);
  }

  T* data() { return data_; }
  const T* data() const { return data_; }
  std::size_t size() const { return size_; }
  T& operator[](std::size_t k) { return data_[k]; }
  const T& operator[](std::size_t k) const { return data_[k]; }

 private:
  std::size_t size_ = 0;
  T* data_ = nullptr;
};

// A big array that is not an image: Exact pages of its own from kOwnPagesMinBytes on.
template <class T>
using BigArray = std::vector<T, OwnPagesAllocator<T>>;

}  // namespace rayview
