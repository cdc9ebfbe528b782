#pragma once
// Small helpers shared by the fuzz targets (fuzz/*_target.cpp). Each target defines LLVMFuzzerTestOneInput;
// it is linked either with libFuzzer (preset "fuzz") or with replay_main.cpp (the regression tests).

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

namespace rayview::fuzz {

inline std::string_view asText(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// A property the target checks does not hold: say which, then abort so libFuzzer keeps the input.
[[noreturn]] inline void fail(const char* what) {
  std::fprintf(stderr, "rayview fuzz: property violated: %s\n", what);
  std::fflush(stderr);
  std::abort();
}

}  // namespace rayview::fuzz
