#pragma once
// How far an image is from a reference image: the figures the speed-for-accuracy trade is judged by.

#include <limits>

#include "rayview/image.h"

namespace rayview {

inline constexpr double kMaxChannelValue = 255.0;

struct ImageError {
  double rmse = 0.0;  // root mean square over every channel of every pixel, in 0..255 units
  double psnrDb = std::numeric_limits<double>::infinity();  // 20 log10(255 / rmse); +inf when identical
  double pctOffByMoreThan1 = 0.0;  // % of pixels with any channel differing by more than 1
  int maxChannelDifference = 0;
};

// 20 log10(255 / rmse); +inf for rmse 0.
double psnrFromRmse(double rmse);

// Throws std::invalid_argument when the sizes differ.
ImageError compareToReference(const Image& image, const Image& reference);

}  // namespace rayview
