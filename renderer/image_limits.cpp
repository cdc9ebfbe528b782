#include "rayview/image_limits.h"

namespace rayview {

std::string imageSizeProblem(long long width, long long height) {
  const std::string size = std::to_string(width) + " x " + std::to_string(height) + " pixels";
  if (width <= 0 || height <= 0) return size + " is not an image (both sides must be positive)";
  if (width > kMaxImageSide || height > kMaxImageSide || width > kMaxImagePixels / height)
    return size + " is too large (the limit is " + std::to_string(kMaxImagePixels) + " pixels, 16384 x 16384, and " +
           std::to_string(kMaxImageSide) + " a side)";
  return {};
}

}  // namespace rayview
