#include "rayview/process_start.h"

#include <chrono>

namespace rayview {
namespace {

std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();

}  // namespace

void captureProcessStart() { start = std::chrono::steady_clock::now(); }

double msSinceProcessStart() {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace rayview
