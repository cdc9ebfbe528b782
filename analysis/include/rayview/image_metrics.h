#pragma once
// How far an image is from a reference image: the figures the speed-for-accuracy trade is judged by.

#include <cstddef>
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
  // The counts the percentages come from: a percentage is printed from them (formatPercent), never rounded up.
  std::size_t pixels = 0, exactPixels = 0, within1Pixels = 0;
  // "" when the image was made with the reference's camera; else why not ("the camera was moved in the viewer",
  // "the image is 640x480, the reference 512x512"), which the figures then say. The comparer sets it, knowing
  // where the image came from.
  std::string cameraMismatch;
};

// 20 log10(255 / rmse); +inf for rmse 0.
double psnrFromRmse(double rmse);

// % of pixels no channel of which differs by more than 1.
inline double pctWithin1(const ImageError& error) { return 100.0 - error.pctOffByMoreThan1; }

// PSNR in dB with two decimals, "inf" for identical images.
std::string formatPsnr(double psnrDb);

// `count` of `total` as a percentage with three decimals, truncated, not rounded: "100.000" only when count is
// total, "0.000" only when it is 0 (99.9996 % is "99.999").
std::string formatPercent(std::size_t count, std::size_t total);

// The figures as `rayview compare` prints them and the viewer's `compare` script command repeats them:
// "exact=97.370% within1=98.321% maxdiff=37 psnr=48.08" (percentages by formatPercent), followed by
// " camera=differs (WHY)" when cameraMismatch says the camera is not the reference's.
std::string comparisonSummary(const ImageError& error);

// Throws std::invalid_argument when the sizes differ.
ImageError compareToReference(const Image& image, const Image& reference);

// A false-colour picture of where two images of the same size differ, by each pixel's largest channel
// difference d: 0 the reference at a quarter of its brightness (so the scene stays recognisable), 1 blue,
// 2..8 yellow, more than 8 red. Throws std::invalid_argument when the sizes differ.
Image differenceImage(const Image& image, const Image& reference);

}  // namespace rayview
