#pragma once
// Which texel of an image a face shows at a point of it: one mapping for the tracer's textures and maps and for the
// cut-outs (rayview/cut_outs.h), so that a hole is exactly where the image's texel says it is.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include <glm/vec2.hpp>

#include "rayview/scene.h"

namespace rayview {

inline constexpr std::size_t kNoTexel = static_cast<std::size_t>(-1);

// The pixel (y * width + x) of `texture` that `face` shows at barycentric weights b1, b2 (of its corners 1 and 2):
// uv interpolated from the face's <texturedata> entries; u to the right, v up (OBJ convention: v = 0 is the bottom
// row of the image); repeat wrap; nearest texel. kNoTexel when uv is not finite. The face must have texture
// coordinates.
inline std::size_t texelIndex(const Texture& texture, const std::vector<glm::vec2>& texCoords,
                              const FaceAttributes& face, float b1, float b2) {
  const float b0 = 1.0f - b1 - b2;
  const glm::vec2 uv =
      b0 * texCoords[face.texCoord[0]] + b1 * texCoords[face.texCoord[1]] + b2 * texCoords[face.texCoord[2]];
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return kNoTexel;
  const float u = uv.x - std::floor(uv.x);
  const float v = uv.y - std::floor(uv.y);
  const int x = std::min(static_cast<int>(u * texture.width), texture.width - 1);
  const int y = std::min(static_cast<int>((1.0f - v) * texture.height), texture.height - 1);
  return static_cast<std::size_t>(y) * texture.width + x;
}

}  // namespace rayview
