#include "reference_compare.h"

#include <utility>

#include "rayview/grid_render.h"

namespace rayview {
namespace {

std::string size(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

}  // namespace

ImageView chooseImageView(bool flipHeld, bool differenceOn, bool comparable) {
  if (!comparable) return ImageView::Render;
  if (flipHeld) return ImageView::Reference;
  return differenceOn ? ImageView::Difference : ImageView::Render;
}

const char* toString(ImageView view) {
  switch (view) {
    case ImageView::Reference:
      return "reference";
    case ImageView::Difference:
      return "difference";
    case ImageView::Render:
      break;
  }
  return "render";
}

bool ReferenceComparison::load(const std::string& path, int imageWidth, int imageHeight) {
  Image image;
  try {
    image = readImageFile(path, "the reference image");  // its message names the file
  } catch (const ImageIoError& error) {
    loadError_ = error.what();
    return false;
  }
  if (imageWidth > 0 && imageHeight > 0 && (image.width != imageWidth || image.height != imageHeight)) {
    loadError_ = path + " is " + size(image.width, image.height) + " but the image is " + size(imageWidth, imageHeight) +
                 ": a reference must be the same size";
    return false;
  }
  path_ = path;
  reference_ = std::move(image);
  ++referenceSerial_;
  loadError_.clear();
  figures_.reset();
  figuresVersion_ = 0;
  return true;
}

std::string ReferenceComparison::sizeProblem(int width, int height) const {
  if (!loaded() || (width == reference_.width && height == reference_.height)) return {};
  return "the image is " + size(width, height) + " but " + path_ + " is " + size(reference_.width, reference_.height) +
         ": not compared";
}

void ReferenceComparison::compareFinal(const Image& frame, std::uint64_t version) {
  if (!comparable(frame.width, frame.height) || (figures_ && figuresVersion_ == version)) return;
  figures_ = compareToReference(frame, reference_);
  figuresVersion_ = version;
}

const Image& ReferenceComparison::difference(const ProgressiveFrame& frame) {
  if (comparable(frame.width, frame.height) &&
      (differenceSerial_ == 0 || differenceOf_ != frame.version || differenceReference_ != referenceSerial_)) {
    // Differenced at the reference's size, block by block, as the coarse pass is seen.
    difference_ = frame.stride > 1
                      ? differenceImage(upscaleBlocks(frame.image, frame.stride, frame.width, frame.height), reference_)
                      : differenceImage(frame.image, reference_);
    differenceOf_ = frame.version;
    differenceReference_ = referenceSerial_;
    ++differenceSerial_;
  }
  return difference_;
}

std::string comparisonLine(const std::string& path, const ImageError& figures) {
  return "compare " + path + " " + comparisonSummary(figures);
}

}  // namespace rayview
