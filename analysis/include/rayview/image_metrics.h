#pragma once
// How far an image is from a reference image: the figures the speed-for-accuracy trade is judged by.

#include <limits>
#include <string>

#include "rayview/image.h"

namespace rayview {

inline constexpr double kMaxChannelValue = 255.0;

struct ImageError {
  double rmse = 0.0;  // root mean square over every channel of every pixel, in 0..255 units
  double psnrDb = std::numeric_limits<double>::infinity();  // 20 log10(255 / rmse); +inf when identical
  double pctOffByMoreThan1 = 0.0;  // % of pixels with any channel differing by more than 1
  double pctExact = 100.0;         // % of pixels identical in every channel
  int maxChannelDifference = 0;
};

// 20 log10(255 / rmse); +inf for rmse 0.
double psnrFromRmse(double rmse);

// % of pixels no channel of which differs by more than 1.
inline double pctWithin1(const ImageError& error) { return 100.0 - error.pctOffByMoreThan1; }

// PSNR in dB with two decimals, "inf" for identical images.
std::string formatPsnr(double psnrDb);

// The figures as `rayview compare` prints them and the viewer's `compare` script command repeats them:
// "exact=97.370% within1=98.321% maxdiff=37 psnr=48.08".
std::string comparisonSummary(const ImageError& error);

// Throws std::invalid_argument when the sizes differ.
ImageError compareToReference(const Image& image, const Image& reference);

// A false-colour picture of where two images of the same size differ, by each pixel's largest channel
// difference d: 0 the reference at a quarter of its brightness (so the scene stays recognisable), 1 blue,
// 2..8 yellow, more than 8 red. Throws std::invalid_argument when the sizes differ.
Image differenceImage(const Image& image, const Image& reference);

}  // namespace rayview
