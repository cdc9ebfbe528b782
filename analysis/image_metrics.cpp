#include "rayview/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace rayview {

double psnrFromRmse(double rmse) {
  if (rmse <= 0.0) return std::numeric_limits<double>::infinity();
  return 20.0 * std::log10(kMaxChannelValue / rmse);
}

std::string formatPsnr(double psnrDb) {
  if (std::isinf(psnrDb)) return "inf";
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", psnrDb);
  return text;
}

std::string formatPercent(std::size_t count, std::size_t total) {
  if (total == 0) return "100.000";
  // In integers: 100000 * count fits 64 bits for any image the size limit allows.
  const unsigned long long thousandths = 100000ULL * count / total;
  char text[32];
  std::snprintf(text, sizeof text, "%llu.%03llu", thousandths / 1000, thousandths % 1000);
  return text;
}

std::string comparisonSummary(const ImageError& error) {
  std::string text = "exact=" + formatPercent(error.exactPixels, error.pixels) + "% within1=" +
                     formatPercent(error.within1Pixels, error.pixels) + "% maxdiff=" +
                     std::to_string(error.maxChannelDifference) + " psnr=" + formatPsnr(error.psnrDb);
  if (!error.cameraMismatch.empty()) text += " camera=differs (" + error.cameraMismatch + ")";
  return text;
}

ImageError compareToReference(const Image& image, const Image& reference) {
  if (image.width != reference.width || image.height != reference.height)
    throw std::invalid_argument("cannot compare a " + std::to_string(image.width) + "x" +
                                std::to_string(image.height) + " image with a " + std::to_string(reference.width) +
                                "x" + std::to_string(reference.height) + " reference");
  ImageError error;
  const std::size_t pixels = static_cast<std::size_t>(image.width) * image.height;
  if (pixels == 0) return error;
  // Integer sums: exact whatever the image size (255^2 * 3 * 2^32 pixels still fits in 64 bits).
  std::uint64_t sumSquares = 0;
  std::size_t offPixels = 0, exactPixels = 0;
  for (std::size_t p = 0; p < pixels; ++p) {
    int worst = 0;
    for (int c = 0; c < 3; ++c) {
      const int d = std::abs(int(image.rgb[3 * p + c]) - int(reference.rgb[3 * p + c]));
      sumSquares += static_cast<std::uint64_t>(d * d);
      if (d > worst) worst = d;
    }
    if (worst > 1) ++offPixels;
    if (worst == 0) ++exactPixels;
    if (worst > error.maxChannelDifference) error.maxChannelDifference = worst;
  }
  error.rmse = std::sqrt(static_cast<double>(sumSquares) / (3.0 * static_cast<double>(pixels)));
  error.psnrDb = psnrFromRmse(error.rmse);
  error.pctOffByMoreThan1 = 100.0 * static_cast<double>(offPixels) / static_cast<double>(pixels);
  error.pctExact = 100.0 * static_cast<double>(exactPixels) / static_cast<double>(pixels);
  error.pixels = pixels;
  error.exactPixels = exactPixels;
  error.within1Pixels = pixels - offPixels;
  return error;
}

Image differenceImage(const Image& image, const Image& reference) {
  if (image.width != reference.width || image.height != reference.height)
    throw std::invalid_argument("cannot compare a " + std::to_string(image.width) + "x" +
                                std::to_string(image.height) + " image with a " + std::to_string(reference.width) +
                                "x" + std::to_string(reference.height) + " reference");
  Image diff(image.width, image.height);
  const std::size_t pixels = static_cast<std::size_t>(image.width) * image.height;
  for (std::size_t p = 0; p < pixels; ++p) {
    int worst = 0;
    for (int c = 0; c < 3; ++c)
      worst = std::max(worst, std::abs(int(image.rgb[3 * p + c]) - int(reference.rgb[3 * p + c])));
    std::uint8_t* out = &diff.rgb[3 * p];
    if (worst == 0) {
      for (int c = 0; c < 3; ++c) out[c] = static_cast<std::uint8_t>(reference.rgb[3 * p + c] / 4);
    } else if (worst == 1) {
      out[0] = 40, out[1] = 90, out[2] = 255;
    } else if (worst <= 8) {
      out[0] = 255, out[1] = 220, out[2] = 0;
    } else {
      out[0] = 255, out[1] = 0, out[2] = 0;
    }
  }
  return diff;
}

}  // namespace rayview
