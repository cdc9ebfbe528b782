// Whether a model file's own camera and lights show the model: cheap tests on the geometry, no tracing, so a file
// whose camera looks away (or sits inside the model) or whose lights are too weak to see by is framed and lit by
// rayview instead (docs/scene-format.md, "Opening models").

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "model_parts.h"
#include "rayview/camera_rays.h"

namespace rayview::model {
namespace {

constexpr int kCells = 64;                    // the coverage grid's cells per side
constexpr std::size_t kMostTriangles = 200000;  // more are sampled evenly: coverage needs no more

struct Projected {
  double x, y;  // 0..1 across and down the frame
  bool inFront;
};

Projected project(const Camera& c, const CameraBasis& b, const glm::dvec3& point) {
  const glm::dvec3 p = point - c.position;
  const double depth = -glm::dot(p, b.w);
  if (!(depth > 0.0)) return {0.0, 0.0, false};
  const double x = glm::dot(p, b.u) / depth * c.nearDistance, y = glm::dot(p, b.v) / depth * c.nearDistance;
  return {(x - c.left) / (c.right - c.left), (c.top - y) / (c.top - c.bottom), true};
}

}  // namespace

double frameCoverage(const Camera& camera, const SceneGeometry& geometry, const Bounds& bounds) {
  if (!cameraProblem(camera).empty() || geometry.triangles.empty()) return 0.0;
  const glm::dvec3& e = camera.position;
  if (e.x >= bounds.lo.x && e.y >= bounds.lo.y && e.z >= bounds.lo.z && e.x <= bounds.hi.x && e.y <= bounds.hi.y &&
      e.z <= bounds.hi.z)
    return 0.0;  // inside the model's box: its nearest faces hide it, or the camera looks out of it
  const CameraBasis basis = cameraBasis(camera);
  std::vector<char> covered(kCells * kCells, 0);
  const std::size_t step = std::max<std::size_t>(1, geometry.triangles.size() / kMostTriangles);
  for (std::size_t t = 0; t < geometry.triangles.size(); t += step) {
    double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
    bool inFront = true;
    for (std::uint32_t v : geometry.triangles[t].vertex) {
      const Projected p = project(camera, basis, geometry.vertices[v]);
      inFront = inFront && p.inFront;
      x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
    }
    if (!inFront || x1 < 0.0 || y1 < 0.0 || x0 > 1.0 || y0 > 1.0) continue;
    // The cells the triangle's projected box overlaps: an over-estimate for slanted triangles, fine for a 5 % test.
    const int i0 = static_cast<int>(std::max(0.0, x0) * kCells), i1 = static_cast<int>(std::min(1.0, x1) * kCells);
    const int j0 = static_cast<int>(std::max(0.0, y0) * kCells), j1 = static_cast<int>(std::min(1.0, y1) * kCells);
    for (int j = j0; j <= std::min(j1, kCells - 1); ++j)
      for (int i = i0; i <= std::min(i1, kCells - 1); ++i) covered[j * kCells + i] = 1;
  }
  return static_cast<double>(std::count(covered.begin(), covered.end(), 1)) / covered.size();
}

float irradianceAt(const std::vector<PointLight>& lights, const glm::dvec3& centre, double radius) {
  double sum = 0.0;
  for (const PointLight& light : lights) {
    // At least a radius away: a light inside the model lights its faces from there, not infinitely.
    const double d = std::max(glm::length(light.position - centre), radius);
    sum += (light.intensity.x + light.intensity.y + light.intensity.z) / 3.0 / (d * d);
  }
  return static_cast<float>(sum);
}

}  // namespace rayview::model
