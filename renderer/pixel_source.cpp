#include "rayview/pixel_source.h"

namespace rayview {

TracedImage::TracedImage(std::shared_ptr<const SceneParameters> parameters, std::shared_ptr<const PreparedGeometry> geometry,
                         const RenderSettings& settings)
    : parameters_(std::move(parameters)),
      geometry_(std::move(geometry)),
      settings_(settings),
      tracer_(*parameters_, *geometry_, settings) {}

}  // namespace rayview
