#pragma once
// Cut-outs (a material's <alphaimage> and <alphacutoff>, docs/scene-format.md): where a face's material has a
// coverage image and the face has texture coordinates, a point whose coverage is below the cutoff is not part of
// the surface. Every traversal back-end asks hides() after a triangle test succeeds, so camera, mirror and shadow
// rays all pass through the hole; a scene without cut-outs has no CutOuts and pays nothing but a null test.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "rayview/scene.h"

namespace rayview {

class CutOuts {
 public:
  // The scene's cut-outs, or null when no material has an alpha image that was read. Keeps pointers into
  // `geometry` (its texture coordinates, faces and images): the geometry must outlive it and not change. The
  // materials' masks and cutoffs are copied: an edit of the parameters does not reach them.
  static std::unique_ptr<const CutOuts> of(const SceneParameters& parameters, const SceneGeometry& geometry);

  // Whether `triangle` is absent at barycentric weights (b1, b2) of its corners 1 and 2: its material has a mask, the
  // face has texture coordinates, uv is finite, and the coverage byte at texelIndex (rayview/texel_lookup.h, the
  // tracer's texel) is below cutoff * 255, compared in float (0.5 hides 0..127 and keeps 128..255).
  bool hides(std::uint32_t triangle, double b1, double b2) const;

  explicit CutOuts(const SceneGeometry& geometry) : geometry_(geometry) {}

 private:
  struct Mask {
    const Texture* image = nullptr;        // null: the material has no cut-out
    const std::uint8_t* coverage = nullptr;  // the image's alpha bytes, else its red bytes
    std::size_t stride = 1;                  // bytes from one pixel's coverage to the next
    float threshold = 0.0f;                  // cutoff * 255
  };
  std::vector<Mask> masks_;  // one per material, in the scene's order
  const SceneGeometry& geometry_;
};

}  // namespace rayview
