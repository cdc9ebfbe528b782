#include "rayview/lean_memory.h"

#include <cstdio>
#include <fstream>
#include <string>

namespace rayview {
namespace {

// Measured peaks of the fast layout were 120-400 bytes a triangle (the most at 1e5 triangles, where the BVH's build
// dominates) and ~13 bytes a pixel (the image, the PNG's filtered copy and output): taken with a margin.
constexpr std::uint64_t kFastBytesPerTriangle = 450;
constexpr std::uint64_t kFastBytesPerPixel = 16;
constexpr std::uint64_t kFixedBytes = std::uint64_t{64} << 20;

std::string gibibytes(std::uint64_t bytes) {
  char text[32];
  const double mib = static_cast<double>(bytes) / double(std::uint64_t{1} << 20);
  if (mib < 1024.0) std::snprintf(text, sizeof text, "%.0f MiB", mib);
  else std::snprintf(text, sizeof text, "%.1f GiB", mib / 1024.0);
  return text;
}

}  // namespace

std::uint64_t estimatedFastPeakBytes(std::size_t triangles, std::size_t pixels) {
  return kFixedBytes + kFastBytesPerTriangle * triangles + kFastBytesPerPixel * pixels;
}

std::uint64_t availableMemoryBytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  std::uint64_t kib = 0;
  std::string unit;
  while (meminfo >> key >> kib >> unit)
    if (key == "MemAvailable:") return kib * 1024;
  return 0;
}

MemoryPlan planMemory(MemoryUse use, std::size_t triangles, std::size_t pixels, std::uint64_t available) {
  if (use == MemoryUse::Lean) return {true, "requested"};
  if (use == MemoryUse::Fast) return {false, "requested"};
  const std::uint64_t estimate = estimatedFastPeakBytes(triangles, pixels);
  if (available == 0) return {false, "available memory unknown"};
  if (estimate > available)
    return {true, "estimated peak " + gibibytes(estimate) + " exceeds the " + gibibytes(available) + " available"};
  return {false, "estimated peak " + gibibytes(estimate) + " fits in " + gibibytes(available) + " available"};
}

std::string_view toString(MemoryUse use) {
  switch (use) {
    case MemoryUse::Auto: return "auto";
    case MemoryUse::Fast: return "fast";
    case MemoryUse::Lean: return "lean";
  }
  return "auto";
}

bool parseMemoryUse(std::string_view text, MemoryUse& out) {
  for (MemoryUse use : {MemoryUse::Auto, MemoryUse::Fast, MemoryUse::Lean})
    if (text == toString(use)) {
      out = use;
      return true;
    }
  return false;
}

}  // namespace rayview
