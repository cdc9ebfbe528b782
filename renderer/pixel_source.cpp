#include "rayview/pixel_source.h"

namespace rayview {

TracedImage::TracedImage(std::shared_ptr<const Scene> scene, std::shared_ptr<const PreparedGeometry> geometry,
                         const RenderSettings& settings)
    : scene_(std::move(scene)),
      geometry_(std::move(geometry)),
      tracer_(*scene_, *geometry_, settings) {}

}  // namespace rayview
