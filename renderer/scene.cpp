#include "rayview/scene.h"

namespace rayview {

bool SceneParameters::hasMirrors() const {
  if (maxRayDepth <= 0) return false;
  for (const Material& m : materials)
    if (m.isMirror()) return true;
  return false;
}

}  // namespace rayview
