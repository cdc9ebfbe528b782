#include "rayview/preview_level.h"

#include <algorithm>

namespace rayview {

std::int64_t levelPixels(int width, int height, int stride) {
  if (width <= 0 || height <= 0 || stride <= 0) return 0;
  const std::int64_t columns = (width + stride - 1) / stride, rows = (height + stride - 1) / stride;
  return columns * rows;
}

int choosePreviewStride(std::span<const PassTime> recent, int width, int height, double budgetMs) {
  double msPerPixel = 0.0;
  int measuredStride = 0;  // of the newest complete pass; 0: none
  for (auto pass = recent.rbegin(); pass != recent.rend(); ++pass) {
    if (pass->pixels <= 0) continue;
    const double perPixel = pass->ms / static_cast<double>(pass->pixels);
    msPerPixel = std::max(msPerPixel, perPixel);
    if (pass->complete) {
      measuredStride = pass->stride;
      break;
    }
  }
  // A cancelled pass only bounds the cost from below: alone, it may say "coarser", never "finer".
  const int finest = measuredStride > 0 ? 1 : kUnmeasuredStride;
  const int refineFrom = measuredStride > 0 ? measuredStride : kUnmeasuredStride;
  for (int stride = finest; stride < kCoarsestStride; stride *= 2) {
    const double budget = stride < refineFrom ? budgetMs * kRefineShare : budgetMs;
    if (msPerPixel * static_cast<double>(levelPixels(width, height, stride)) <= budget) return stride;
  }
  return kCoarsestStride;
}

int chooseEditStride(std::span<const PassTime> recent, int width, int height) {
  if (choosePreviewStride(recent, width, height, kWholeFrameFirstPassMs) == 1) return 1;
  return std::max(kFinestEditPreviewStride, choosePreviewStride(recent, width, height, kFirstPassBudgetMs));
}

int nextPassStride(int firstStride, int stride) {
  if (stride <= 1) return 0;
  if (firstStride >= kIntermediateAfter && stride > kIntermediateStride) return kIntermediateStride;
  return 1;
}

}  // namespace rayview
