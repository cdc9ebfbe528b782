#pragma once
// The bytes of an image: pages of their own from 512 KiB on (rayview/own_pages.h, rounded up to whole huge pages), and
// value-less construction leaves them unwritten, so that a frame rendered whole is first touched by the threads that
// render it, not zeroed page by page by one thread first (docs/PERFORMANCE.md, "Fresh pages").

#include <cstddef>
#include <cstdint>
#include <new>
#include <utility>
#include <vector>

#include "rayview/own_pages.h"

namespace rayview {

template <class T>
struct PixelAllocator : OwnPagesAllocator<T, OwnPages::RoundedUp> {
  template <class U>
  struct rebind {
    using other = PixelAllocator<U>;
  };
  PixelAllocator() = default;
  template <class U>
  PixelAllocator(const PixelAllocator<U>&) noexcept {}

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
