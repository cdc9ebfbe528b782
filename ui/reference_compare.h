#pragma once
// Comparing the render with a reference image (the course's, or the output of the user's own ray tracer): the
// reference, the figures of the newest final pass against it, the false-colour difference, and which image the
// viewer shows. No GL: the viewer uploads what this hands it.

#include <cstdint>
#include <optional>
#include <string>

#include "rayview/image.h"
#include "rayview/image_metrics.h"
#include "rayview/progressive_renderer.h"

namespace rayview {

// What the image area shows.
enum class ImageView { Render, Reference, Difference };

// Holding the flip key shows the reference, otherwise the difference view shows when it is on. Both need a
// reference the size of the image on screen (`comparable`); without one the render shows.
ImageView chooseImageView(bool flipHeld, bool differenceOn, bool comparable);
const char* toString(ImageView view);  // "render", "reference", "difference"

class ReferenceComparison {
 public:
  // Reads `path` (PNG, PPM or JPEG). With `imageWidth` and `imageHeight` above 0 (a scene is on screen) the
  // reference must be that size. On success it replaces the reference and forgets the figures of the previous
  // one; on failure the previous reference stays and loadError() says why, naming the file.
  bool load(const std::string& path, int imageWidth, int imageHeight);

  bool loaded() const { return reference_.width > 0; }
  const std::string& path() const { return path_; }
  const Image& reference() const { return reference_; }
  // Increases with every reference loaded (the texture is uploaded again).
  std::uint64_t referenceSerial() const { return referenceSerial_; }
  // Why the newest load failed; "" when it did not.
  const std::string& loadError() const { return loadError_; }
  // Why an image of this size cannot be compared with the reference ("" when it can, or when there is none).
  std::string sizeProblem(int width, int height) const;
  bool comparable(int width, int height) const { return loaded() && sizeProblem(width, height).empty(); }

  // A final pass: its figures against the reference, once per frame version (nothing when the sizes differ).
  void compareFinal(const Image& frame, std::uint64_t version);
  // The figures of the last final pass compared, and that frame's version.
  const std::optional<ImageError>& figures() const { return figures_; }
  std::uint64_t figuresVersion() const { return figuresVersion_; }

  // The false-colour difference (rayview/image_metrics.h) of `frame`, any pass (a coarse one as its blocks),
  // with the reference; computed again only for another frame version or reference. Needs comparable(frame's
  // size).
  const Image& difference(const ProgressiveFrame& frame);
  // Increases whenever difference() computes a new image (the texture is uploaded again).
  std::uint64_t differenceSerial() const { return differenceSerial_; }

 private:
  std::string path_;
  Image reference_;
  std::uint64_t referenceSerial_ = 0;
  std::string loadError_;
  std::optional<ImageError> figures_;
  std::uint64_t figuresVersion_ = 0;
  Image difference_;
  std::uint64_t differenceOf_ = 0, differenceReference_ = 0;  // the frame version and reference it shows
  std::uint64_t differenceSerial_ = 0;
};

// What the `compare PATH` script command prints: "compare PATH exact=E% within1=W% maxdiff=M psnr=P".
std::string comparisonLine(const std::string& path, const ImageError& figures);

}  // namespace rayview
