#pragma once
// Private: the reference bounding-volume hierarchy, entirely in double precision. Binned SAH build,
// iterative traversal with ordered children and a fixed stack, conservative box tests (Ize, "Robust BVH
// Ray Traversal", JCGT 2(2), 2013) and the watertight triangle test, so that no ray is lost between the box
// level and the triangle level.

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "rayview/accel.h"
#include "rayview/cut_outs.h"
#include "watertight_triangle.h"

namespace rayview {

struct BvhRay {
  glm::dvec3 origin{0.0};
  glm::dvec3 direction{0.0};  // finite, non-zero
  double tNear = 0.0;
  double tFar = 0.0;
  std::uint32_t excludedTriangle = kNoTriangle;  // never reported (the triangle a secondary ray leaves)
};

struct BvhHit {
  TriangleHit hit;
  std::uint32_t triangle = 0;  // index into the triangle list given to build()
};

class ReferenceBvh {
 public:
  // The build never makes a tree deeper than this, so traversal needs no bigger stack.
  static constexpr int kMaxDepth = 64;

  // `vertices` are relative to the accelerator's origin. Triangles that are degenerate (exactly zero
  // area), non-finite or out of range are left out. Returns nullptr when `progress` cancels.
  static std::unique_ptr<ReferenceBvh> build(const SceneArray<glm::dvec3>& vertices,
                                             const SceneArray<Triangle>& triangles, BuildProgress progress,
                                             void* progressUser);
  // A hit `cutOuts` hides is no hit (null, the default, for a scene without cut-outs); it must outlive the BVH.
  void setCutOuts(const CutOuts* cutOuts) { cutOuts_ = cutOuts; }

  bool closestHit(const BvhRay& ray, BvhHit& out) const;
  bool occluded(const BvhRay& ray) const;

  std::size_t nodeCount() const { return nodes_.size(); }
  std::size_t triangleCount() const { return triangles_.size(); }

  struct Node {
    glm::dvec3 lower{0.0}, upper{0.0};
    std::uint32_t first = 0;  // leaf: first entry in triangles_; inner node: left child (right = first + 1)
    std::uint32_t count = 0;  // leaf: number of triangles; 0 for an inner node
  };
  struct LeafTriangle {
    glm::dvec3 v0, v1, v2;
    std::uint32_t id;
  };

 private:
  friend class ReferenceBvhBuilder;
  template <bool kAnyHit>
  bool traverse(const BvhRay& ray, BvhHit* out) const;

  std::vector<Node> nodes_;                // nodes_[0] is the root
  std::vector<LeafTriangle> triangles_;    // in leaf order, vertices gathered for locality
  const CutOuts* cutOuts_ = nullptr;
};

}  // namespace rayview
