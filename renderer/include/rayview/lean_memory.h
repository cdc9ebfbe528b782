#pragma once
// The lean layout: a render that holds less memory at some cost in speed, for a machine where the fast one would
// not fit. Lean is rayview's packet BVH with leaves of up to kLeanLeafTriangles (its build adds ~40 bytes a triangle
// at its peak where Embree's adds ~120; rays 1.3-1.5x slower) and, in `rayview render`, the image kept deflated in
// bands while the scene is held (renderFrameDeflated). Fast is Embree (or the packet BVH for small scenes) and the
// whole image. `rayview render` chooses lean only on request or when the fast layout's estimated peak would not fit
// in the memory the kernel says is available; everything else is always fast.

#include <cstddef>
#include <cstdint>
#include <string>

namespace rayview {

inline constexpr std::size_t kLeanLeafTriangles = 3;

enum class MemoryUse { Auto, Fast, Lean };

struct MemoryPlan {
  bool lean = false;
  std::string reason;  // for the summary: "requested", "estimated peak 2.1 GiB fits in 18.3 GiB available", ...
};

// A generous estimate of the fast layout's peak for a render of `triangles` into `pixels` pixels: the scene's
// arrays, Embree's BVH and its build, the image and its PNG, the libraries.
std::uint64_t estimatedFastPeakBytes(std::size_t triangles, std::size_t pixels);

// The kernel's estimate of the memory available to a new process (MemAvailable in /proc/meminfo); 0 if unknown.
std::uint64_t availableMemoryBytes();

// Lean when asked for, or (Auto) when the fast estimate exceeds `available` (unknown: fast).
MemoryPlan planMemory(MemoryUse use, std::size_t triangles, std::size_t pixels, std::uint64_t available);

std::string_view toString(MemoryUse use);
bool parseMemoryUse(std::string_view text, MemoryUse& out);

}  // namespace rayview
