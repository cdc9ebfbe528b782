#include "compare_command.h"

#include <cstdio>
#include <stdexcept>

#include "rayview/image.h"
#include "rayview/image_metrics.h"
#include "rayview/input_files.h"

namespace rayview {

int runCompareCommand(const CommandLine& command) {
  Image image, reference;
  try {
    image = readImageFile(command.images[0], "the image compared");
    reference = readImageFile(command.images[1], "the reference image");
  } catch (const ImageIoError& error) {
    std::fprintf(stderr, "rayview: error: %s\n", error.what());
    return kExitBadInput;
  }
  // Refused before any figure is printed: the difference map never replaces an image it was made from.
  if (const std::string problem = outputReplacesInput(command.diffPath); !command.diffPath.empty() && !problem.empty()) {
    std::fprintf(stderr, "rayview: error: %s\n", problem.c_str());
    return kExitBadInput;
  }
  if (image.width != reference.width || image.height != reference.height) {
    std::fprintf(stderr, "rayview: error: %s is %dx%d but %s is %dx%d: images of different sizes cannot be compared\n",
                 command.images[0].c_str(), image.width, image.height, command.images[1].c_str(),
                 reference.width, reference.height);
    return kExitBadInput;
  }
  const ImageError error = compareToReference(image, reference);
  const double within1 = pctWithin1(error);
  std::printf("%s\n", comparisonSummary(error).c_str());
  if (!command.diffPath.empty()) {
    try {
      writeImageFile(command.diffPath, differenceImage(image, reference));
    } catch (const ImageIoError& failure) {
      std::fprintf(stderr, "rayview: error: %s\n", failure.what());
      return kExitBadInput;
    }
  }
  // Decided on the exact counts; the message gives them, and a truncated percentage that never reads as the
  // requirement met ("100.000 %" only when every pixel is within 1).
  if (within1 < command.minWithin1) {
    std::fprintf(stderr, "rayview: %s%% of the pixels (%zu of %zu) are within 1 of the reference, %g%% required\n",
                 formatPercent(error.within1Pixels, error.pixels).c_str(), error.within1Pixels, error.pixels,
                 command.minWithin1);
    return 1;
  }
  return kExitOk;
}

}  // namespace rayview
