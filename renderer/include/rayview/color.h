#pragma once
// Radiance and colours, in the file's 0..255 units.

#include <glm/vec3.hpp>

namespace rayview {

using Color = glm::vec3;

}  // namespace rayview
