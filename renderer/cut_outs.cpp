#include "rayview/cut_outs.h"

#include "rayview/texel_lookup.h"

namespace rayview {

std::unique_ptr<const CutOuts> CutOuts::of(const SceneParameters& parameters, const SceneGeometry& geometry) {
  auto cutOuts = std::make_unique<CutOuts>(geometry);
  bool any = false;
  for (const Material& material : parameters.materials) {
    Mask mask;
    const Texture* image = geometry.textureNamed(material.alphaImage);
    if (image && !image->opaqueAlpha) {  // an alpha 255 everywhere hides nothing
      const bool alpha = !image->alpha.empty();
      mask = {image, alpha ? image->alpha.data() : image->rgb.data(), alpha ? 1u : 3u, material.alphaCutoff * 255.0f};
      any = true;
    }
    cutOuts->masks_.push_back(mask);
  }
  if (!any) return nullptr;
  return cutOuts;
}

bool CutOuts::hides(std::uint32_t triangle, double b1, double b2) const {
  const std::uint32_t material = geometry_.materialOf(triangle);
  if (material >= masks_.size()) return false;
  const Mask& mask = masks_[material];
  if (!mask.image) return false;
  const FaceAttributes& face = geometry_.attributesOf(triangle);
  if (!face.hasTexCoords()) return false;
  const std::size_t at =
      texelIndex(*mask.image, geometry_.texCoords, face, static_cast<float>(b1), static_cast<float>(b2));
  return at != kNoTexel && static_cast<float>(mask.coverage[at * mask.stride]) < mask.threshold;
}

}  // namespace rayview
