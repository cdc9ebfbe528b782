// Exposure keys, the reference beside the scene, and the projection used to draw lights, the pivot and outlines.
#include "view_habits.h"

#include <algorithm>
#include <filesystem>
#include <system_error>

#include <glm/glm.hpp>

namespace rayview {

double stepExposure(double stops, int steps) {
  return std::clamp(stops + kExposureKeyStops * steps, double{kMinExposureStops}, double{kMaxExposureStops});
}

std::optional<std::string> referenceBeside(const std::string& scenePath) {
  if (scenePath.empty()) return std::nullopt;
  for (const char* extension : {".png", ".ppm"}) {
    const std::filesystem::path candidate = std::filesystem::path(scenePath).replace_extension(extension);
    std::error_code error;
    if (std::filesystem::is_regular_file(candidate, error)) return candidate.string();
  }
  return std::nullopt;
}

std::optional<ScreenPoint> projectToScreen(const glm::dvec3& p, const Camera& camera, float x, float y, float width,
                                           float height) {
  // The course's camera: u = gaze x up, v = u x gaze; the near plane at nearDistance along the gaze.
  const glm::dvec3 forward = glm::normalize(camera.gaze);
  const glm::dvec3 right = glm::normalize(glm::cross(camera.gaze, camera.up));
  const glm::dvec3 up = glm::cross(right, forward);
  const glm::dvec3 d = p - camera.position;
  const double depth = glm::dot(d, forward);
  if (!(depth > 1e-9) || camera.right == camera.left || camera.top == camera.bottom) return std::nullopt;
  const double s = glm::dot(d, right) * camera.nearDistance / depth;
  const double t = glm::dot(d, up) * camera.nearDistance / depth;
  return ScreenPoint{x + static_cast<float>((s - camera.left) / (camera.right - camera.left)) * width,
                     y + static_cast<float>((camera.top - t) / (camera.top - camera.bottom)) * height};
}

}  // namespace rayview
