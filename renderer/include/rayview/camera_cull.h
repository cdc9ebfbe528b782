#pragma once
// Which camera rays need no traversal: those that provably pass beside every one of the accel's boxes (Accel::boxes),
// whose answer is the background. Most of a small model's image is background, and a packet of misses still cost
// its rays' set-up and a traversal.

#include <vector>

#include "rayview/accel.h"
#include "rayview/camera_rays.h"

namespace rayview {

class CameraCull {
 public:
  // `eye`: the camera's position relative to the boxes' origin.
  CameraCull(const Camera& camera, const CameraBasis& basis, const glm::dvec3& eye, const std::vector<AccelBox>& boxes);

  // True when every camera ray through image coordinates (i, j) with i0 <= i <= i1 and j0 <= j <= j1 (the
  // pixelDirection arguments) misses every box. Conservative: false whenever in doubt, by margins far beyond the
  // rounding of the rays and of the triangle tests.
  bool misses(double i0, double i1, double j0, double j1) const;

 private:
  // Where a box in front of the eye is seen: the bounds, in image coordinates, of its corners' projections, widened.
  struct Seen {
    double i0, i1, j0, j1;
  };
  std::vector<Seen> seen_;
};

}  // namespace rayview
