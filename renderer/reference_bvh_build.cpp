// The reference BVH build: binned SAH over triangle centroids, O(n log n), iterative (no recursion).
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "reference_bvh.h"

namespace rayview {
namespace {

constexpr int kBins = 16;
constexpr std::uint32_t kMaxLeafSize = 8;
constexpr double kTraversalCost = 1.0;  // one box-pair visit, in units of one triangle test
// From this depth on, splits are object medians: each halves the count, so no leaf is deeper than
// kMedianSplitDepth + 32 <= ReferenceBvh::kMaxDepth for up to 2^32 triangles.
constexpr int kMedianSplitDepth = ReferenceBvh::kMaxDepth - 32;
// Node boxes are widened by this fraction of their largest coordinate magnitude. Exact bounds plus Ize's
// conservative slab test already keep every ray that truly meets the box; the margin also keeps rays that
// only the triangle test's rounding (in the sheared frame, ~1e-16 relative) puts on a triangle.
constexpr double kBoundsMargin = 0x1p-40;
// Progress is reported this many times over the build (plus at the start and the end).
constexpr int kProgressSteps = 64;

constexpr double kInfinity = std::numeric_limits<double>::infinity();

struct Box {
  glm::dvec3 lower{kInfinity}, upper{-kInfinity};

  void grow(const glm::dvec3& p) {
    lower = glm::min(lower, p);
    upper = glm::max(upper, p);
  }
  void grow(const Box& b) {
    lower = glm::min(lower, b.lower);
    upper = glm::max(upper, b.upper);
  }
  // Half the surface area; zero for an empty or flat-in-two-axes box.
  double halfArea() const {
    if (!(lower.x <= upper.x)) return 0.0;
    const glm::dvec3 e = upper - lower;
    return e.x * e.y + e.y * e.z + e.z * e.x;
  }
};

struct Primitive {
  Box box;
  glm::dvec3 centroid;
  std::uint32_t triangle;
};

bool isFinite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

double maxAbs(const glm::dvec3& v) { return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}); }

struct Split {
  int axis = -1;
  int bin = 0;  // primitives in bins [0, bin] go left
  double cost = kInfinity;
};

}  // namespace

class ReferenceBvhBuilder {
 public:
  ReferenceBvhBuilder(ReferenceBvh& bvh, const SceneArray<glm::dvec3>& vertices,
                      const SceneArray<Triangle>& triangles, BuildProgress progress, void* progressUser)
      : bvh_(bvh), vertices_(vertices), triangles_(triangles), progress_(progress), progressUser_(progressUser) {}

  bool run() {
    if (!report(0.0)) return false;
    collectPrimitives();
    if (!primitives_.empty()) {
      bvh_.nodes_.reserve(primitives_.size() / 2 + 1);
      bvh_.triangles_.reserve(primitives_.size());
      bvh_.nodes_.emplace_back();
      std::vector<Task> tasks{{0, 0, static_cast<std::uint32_t>(primitives_.size()), 0}};
      while (!tasks.empty()) {
        const Task task = tasks.back();
        tasks.pop_back();
        if (!buildNode(task, tasks)) return false;
      }
    }
    return report(1.0);
  }

 private:
  struct Task {
    std::uint32_t node, begin, end;
    int depth;
  };

  void collectPrimitives() {
    primitives_.reserve(triangles_.size());
    for (std::size_t i = 0; i < triangles_.size(); ++i) {
      const Triangle& t = triangles_[i];
      if (t.vertex[0] >= vertices_.size() || t.vertex[1] >= vertices_.size() || t.vertex[2] >= vertices_.size())
        continue;
      const glm::dvec3 &a = vertices_[t.vertex[0]], &b = vertices_[t.vertex[1]], &c = vertices_[t.vertex[2]];
      if (!isFinite(a) || !isFinite(b) || !isFinite(c)) continue;
      if (glm::cross(b - a, c - a) == glm::dvec3(0.0)) continue;  // zero area: no ray can hit it
      Primitive p;
      p.box.grow(a);
      p.box.grow(b);
      p.box.grow(c);
      p.centroid = 0.5 * (p.box.lower + p.box.upper);
      p.triangle = static_cast<std::uint32_t>(i);
      primitives_.push_back(p);
    }
  }

  bool buildNode(const Task& task, std::vector<Task>& tasks) {
    Box bounds, centroids;
    for (std::uint32_t i = task.begin; i < task.end; ++i) {
      bounds.grow(primitives_[i].box);
      centroids.grow(primitives_[i].centroid);
    }
    ReferenceBvh::Node& node = bvh_.nodes_[task.node];
    const double margin = kBoundsMargin * std::max(maxAbs(bounds.lower), maxAbs(bounds.upper)) +
                          std::numeric_limits<double>::denorm_min();
    node.lower = bounds.lower - margin;
    node.upper = bounds.upper + margin;

    const std::uint32_t count = task.end - task.begin;
    std::uint32_t middle = task.begin;
    if (task.depth >= kMedianSplitDepth) {
      if (count <= kMaxLeafSize) return makeLeaf(node, task);
      middle = medianSplit(task, centroids);
    } else {
      const Split split = findSplit(task, centroids);
      const double area = bounds.halfArea();
      const bool leafIsCheaper = !(split.cost + kTraversalCost * area < area * count);
      if (count <= kMaxLeafSize && (split.axis < 0 || leafIsCheaper)) return makeLeaf(node, task);
      middle = split.axis < 0 ? medianSplit(task, centroids) : partition(task, centroids, split);
    }

    const auto left = static_cast<std::uint32_t>(bvh_.nodes_.size());
    bvh_.nodes_.emplace_back();
    bvh_.nodes_.emplace_back();
    bvh_.nodes_[task.node].first = left;  // `node` may dangle after emplace_back
    bvh_.nodes_[task.node].count = 0;
    tasks.push_back({left + 1, middle, task.end, task.depth + 1});
    tasks.push_back({left, task.begin, middle, task.depth + 1});
    return true;
  }

  static int binOf(double c, double lower, double scale) {
    return std::clamp(static_cast<int>((c - lower) * scale), 0, kBins - 1);
  }

  // The cheapest binned SAH split, cost = area(left) * count(left) + area(right) * count(right).
  Split findSplit(const Task& task, const Box& centroids) const {
    Split best;
    for (int axis = 0; axis < 3; ++axis) {
      const double extent = centroids.upper[axis] - centroids.lower[axis];
      if (!(extent > 0.0)) continue;
      const double scale = kBins / extent;
      std::array<Box, kBins> boxes;
      std::array<std::uint32_t, kBins> counts{};
      for (std::uint32_t i = task.begin; i < task.end; ++i) {
        const int b = binOf(primitives_[i].centroid[axis], centroids.lower[axis], scale);
        boxes[b].grow(primitives_[i].box);
        ++counts[b];
      }
      std::array<double, kBins> rightCost{};
      Box right;
      std::uint32_t rightCount = 0;
      for (int b = kBins - 1; b > 0; --b) {
        right.grow(boxes[b]);
        rightCount += counts[b];
        rightCost[b] = right.halfArea() * rightCount;
      }
      Box left;
      std::uint32_t leftCount = 0;
      for (int b = 0; b < kBins - 1; ++b) {
        left.grow(boxes[b]);
        leftCount += counts[b];
        if (leftCount == 0 || leftCount == task.end - task.begin) continue;
        const double cost = left.halfArea() * leftCount + rightCost[b + 1];
        if (cost < best.cost) best = {axis, b, cost};
      }
    }
    return best;
  }

  std::uint32_t partition(const Task& task, const Box& centroids, const Split& split) {
    const int axis = split.axis;
    const double lower = centroids.lower[axis];
    const double scale = kBins / (centroids.upper[axis] - lower);
    auto it = std::partition(primitives_.begin() + task.begin, primitives_.begin() + task.end,
                             [&](const Primitive& p) { return binOf(p.centroid[axis], lower, scale) <= split.bin; });
    return static_cast<std::uint32_t>(it - primitives_.begin());
  }

  // Halves the range along the widest centroid axis (any halving when all centroids coincide).
  std::uint32_t medianSplit(const Task& task, const Box& centroids) {
    const glm::dvec3 extent = centroids.upper - centroids.lower;
    const int axis = extent.x >= extent.y ? (extent.x >= extent.z ? 0 : 2) : (extent.y >= extent.z ? 1 : 2);
    const std::uint32_t middle = task.begin + (task.end - task.begin) / 2;
    std::nth_element(primitives_.begin() + task.begin, primitives_.begin() + middle, primitives_.begin() + task.end,
                     [axis](const Primitive& a, const Primitive& b) { return a.centroid[axis] < b.centroid[axis]; });
    return middle;
  }

  bool makeLeaf(ReferenceBvh::Node& node, const Task& task) {
    node.first = static_cast<std::uint32_t>(bvh_.triangles_.size());
    node.count = task.end - task.begin;
    for (std::uint32_t i = task.begin; i < task.end; ++i) {
      const Triangle& t = triangles_[primitives_[i].triangle];
      bvh_.triangles_.push_back({vertices_[t.vertex[0]], vertices_[t.vertex[1]], vertices_[t.vertex[2]],
                                 primitives_[i].triangle});
    }
    placed_ += node.count;
    if (placed_ >= nextReport_) {
      nextReport_ = placed_ + std::max<std::size_t>(1, primitives_.size() / kProgressSteps);
      return report(static_cast<double>(placed_) / static_cast<double>(primitives_.size()));
    }
    return true;
  }

  bool report(double fraction) const { return !progress_ || progress_(progressUser_, fraction); }

 private:
  ReferenceBvh& bvh_;
  const SceneArray<glm::dvec3>& vertices_;
  const SceneArray<Triangle>& triangles_;
  BuildProgress progress_;
  void* progressUser_;
  std::vector<Primitive> primitives_;
  std::size_t placed_ = 0;
  std::size_t nextReport_ = 0;
};

std::unique_ptr<ReferenceBvh> ReferenceBvh::build(const SceneArray<glm::dvec3>& vertices,
                                                  const SceneArray<Triangle>& triangles, BuildProgress progress,
                                                  void* progressUser) {
  auto bvh = std::make_unique<ReferenceBvh>();
  ReferenceBvhBuilder builder(*bvh, vertices, triangles, progress, progressUser);
  if (!builder.run()) return nullptr;
  return bvh;
}

}  // namespace rayview
