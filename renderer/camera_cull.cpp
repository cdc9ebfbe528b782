#include "rayview/camera_cull.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

namespace rayview {

namespace {

double norm1(const glm::dvec3& v) { return std::fabs(v.x) + std::fabs(v.y) + std::fabs(v.z); }

// Relative slack on every rounded term: the rays and the triangle tests round at about 1e-16 of theirs.
constexpr double kSlack = 1e-9;
constexpr double kNowhere = std::numeric_limits<double>::infinity();

}  // namespace

CameraCull::CameraCull(const Camera& camera, const CameraBasis& basis, const glm::dvec3& eye,
                       const std::vector<AccelBox>& boxes) {
  const double n = camera.nearDistance;
  const double across = camera.width / std::fabs(camera.right - camera.left);  // pixels per unit of u
  const double down = camera.height / std::fabs(camera.top - camera.bottom);
  const double uTerms = n + std::fabs(camera.left) + std::fabs(camera.right);
  const double vTerms = n + std::fabs(camera.top) + std::fabs(camera.bottom);
  // Which way i and j grow with u and v.
  const bool iWithU = camera.right > camera.left, jWithV = camera.top < camera.bottom;
  for (const AccelBox& box : boxes) {
    struct Point {
      double x, y, z, scale;  // along u, v and -w from the eye; the size of the terms each rounds relative to
    };
    Point corners[8];
    for (int k = 0; k < 8; ++k) {
      const glm::dvec3 p((k & 1) ? box.upper.x : box.lower.x, (k & 2) ? box.upper.y : box.lower.y,
                         (k & 4) ? box.upper.z : box.lower.z);
      const glm::dvec3 d = p - eye;
      Point& c = corners[k];
      c.x = glm::dot(d, basis.u), c.y = glm::dot(d, basis.v), c.z = -glm::dot(d, basis.w);
      c.scale = std::fabs(c.x) + std::fabs(c.y) + std::fabs(c.z) + norm1(eye) + norm1(p);
    }
    Seen seen{kNowhere, -kNowhere, kNowhere, -kNowhere};
    bool bounded = true;
    // Where an edge crosses the eye's plane (z = 0), the edge is seen from its front corner out to infinity,
    // toward the crossing's x and y: the bounds open that way (both ways where the sign is in doubt).
    const auto onEyePlane = [&](double x, double y, double slack) {
      const bool uUp = x > -slack, uDown = x < slack, vUp = y > -slack, vDown = y < slack;
      if (iWithU ? uUp : uDown) seen.i1 = kNowhere;
      if (iWithU ? uDown : uUp) seen.i0 = -kNowhere;
      if (jWithV ? vUp : vDown) seen.j1 = kNowhere;
      if (jWithV ? vDown : vUp) seen.j0 = -kNowhere;
    };
    // A ray's points have z >= 0: only the box's part in front of the eye can be hit. Its corners there are seen
    // where they project; where its edges cross the eye's plane, toward infinity.
    for (int k = 0; k < 8; ++k) {
      const Point& c = corners[k];
      const double slack = kSlack * c.scale;
      if (c.z < -slack) continue;
      if (!(c.z > slack)) {
        bounded = false;  // on the eye's plane, as far as rounding can tell: it may be seen anywhere
        continue;
      }
      // pixelColumnPart's u = left + (right - left) (i + 0.5) / width solved for i, and the same for j.
      const double u = n * c.x / c.z, v = n * c.y / c.z;
      const double i = (u - camera.left) / (camera.right - camera.left) * camera.width - 0.5;
      const double j = (camera.top - v) / (camera.top - camera.bottom) * camera.height - 0.5;
      if (!std::isfinite(i) || !std::isfinite(j)) {
        bounded = false;
        continue;
      }
      const double error = kSlack * (n + std::fabs(u) + std::fabs(v)) * c.scale / c.z;  // of u and v
      const double di = kSlack * (std::fabs(u) + uTerms) * across + error * across + 1e-6;
      const double dj = kSlack * (std::fabs(v) + vTerms) * down + error * down + 1e-6;
      seen.i0 = std::min(seen.i0, i - di), seen.i1 = std::max(seen.i1, i + di);
      seen.j0 = std::min(seen.j0, j - dj), seen.j1 = std::max(seen.j1, j + dj);
      for (int axis = 0; axis < 3; ++axis) {
        const Point& b = corners[k ^ (1 << axis)];
        const double bSlack = kSlack * b.scale;
        if (!(b.z < -bSlack)) continue;  // not across the plane (a corner on it made the box unbounded)
        const double t = c.z / (c.z - b.z);
        onEyePlane(c.x + t * (b.x - c.x), c.y + t * (b.y - c.y), kSlack * std::max(c.scale, b.scale));
      }
    }
    // Not a number anywhere (a degenerate camera): seen anywhere.
    if (!bounded || std::isnan(seen.i0) || std::isnan(seen.i1) || std::isnan(seen.j0) || std::isnan(seen.j1))
      seen = Seen{-kNowhere, kNowhere, -kNowhere, kNowhere};
    if (seen.i0 <= seen.i1 && seen.j0 <= seen.j1) seen_.push_back(seen);
  }
}

bool CameraCull::misses(double i0, double i1, double j0, double j1) const {
  // A box's part in front of the eye is seen within the hull of its corners' projections, stretched to infinity
  // toward its points on the eye's plane: within the bounds above. A ray through a point outside them misses it.
  for (const Seen& s : seen_)
    if (!(i1 < s.i0 || i0 > s.i1 || j1 < s.j0 || j0 > s.j1)) return false;
  return true;
}

}  // namespace rayview
