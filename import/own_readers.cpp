// rayview's own PLY and STL readers (placeholder: Assimp reads them).
#include "model_parts.h"

namespace rayview::model {

bool readPlyOrStl(const std::filesystem::path&, SceneGeometry&, Notes&) { return false; }

}  // namespace rayview::model
