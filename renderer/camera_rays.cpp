#include "rayview/camera_rays.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

namespace rayview {

std::string cameraProblem(const Camera& camera) {
  const double gazeLength = glm::length(camera.gaze);
  if (!(gazeLength > 0.0) || !std::isfinite(gazeLength)) return "the gaze vector is zero";
  const double upLength = glm::length(camera.up);
  if (!(upLength > 0.0) || !std::isfinite(upLength)) return "the up vector is zero";
  const double sine = glm::length(glm::cross(camera.gaze / gazeLength, camera.up / upLength));
  if (!(sine > 1e-9)) return "the up vector is parallel to the gaze";
  if (!(camera.left != camera.right)) return "the near plane has left = right";
  if (!(camera.bottom != camera.top)) return "the near plane has bottom = top";
  if (!(camera.nearDistance > 0.0)) return "the near distance must be positive";
  if (camera.width <= 0 || camera.height <= 0) return "the image resolution must be positive";
  return {};
}

CameraBasis cameraBasis(const Camera& camera) {
  if (std::string problem = cameraProblem(camera); !problem.empty()) throw std::invalid_argument(problem);
  CameraBasis basis;
  basis.w = -glm::normalize(camera.gaze);
  basis.u = glm::normalize(glm::cross(camera.up, basis.w));
  basis.v = glm::cross(basis.w, basis.u);
  return basis;
}

glm::dvec3 pixelColumnPart(const Camera& camera, const CameraBasis& basis, double i) {
  const double su = camera.left + (camera.right - camera.left) * (i + 0.5) / camera.width;
  return -camera.nearDistance * basis.w + su * basis.u;
}

glm::dvec3 pixelRowPart(const Camera& camera, const CameraBasis& basis, double j) {
  const double sv = camera.top - (camera.top - camera.bottom) * (j + 0.5) / camera.height;
  return sv * basis.v;
}

glm::dvec3 pixelDirection(const Camera& camera, const CameraBasis& basis, double i, double j) {
  return pixelColumnPart(camera, basis, i) + pixelRowPart(camera, basis, j);
}

}  // namespace rayview
