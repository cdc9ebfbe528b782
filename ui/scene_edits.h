#pragma once
// What the viewer lets the user change in a loaded scene, and what each change costs.
//
// Everything here is cheap to change: camera, lights, materials, depth, background. Geometry is not
// editable, so an edit never needs a new BVH; it only needs a new scene snapshot and a render restart.

#include <string>
#include <vector>

#include "rayview/render_settings.h"
#include "rayview/scene.h"

namespace rayview {

struct SceneEdits {
  int maxRayDepth = 0;
  Color background{0.0f};
  Camera camera;
  Color ambientLight{0.0f};
  std::vector<PointLight> pointLights;
  std::vector<TriangularLight> triangularLights;
  std::vector<Material> materials;  // ids and order as loaded: triangles refer to them by index
};

// Largest image the viewer renders (each side, and in total), so a typo in a field cannot exhaust memory.
inline constexpr int kMaxViewerImageSide = 16384;
inline constexpr long long kMaxViewerImagePixels = 64LL * 1024 * 1024;

SceneEdits editsOf(const Scene& scene);
void applyEdits(const SceneEdits& edits, Scene& scene);

bool sameCamera(const Camera& a, const Camera& b);
bool sameEdits(const SceneEdits& a, const SceneEdits& b);

enum class EditEffect {
  None,     // nothing the image depends on changed (or only display settings)
  Restart,  // new snapshot + restart on the same geometry
  Rebuild,  // another traversal back-end: the geometry must be prepared again
};

EditEffect classifyEdit(const SceneEdits& before, const RenderSettings& beforeSettings, const SceneEdits& after,
                        const RenderSettings& afterSettings);

// Empty when the edits describe a scene that can be rendered; otherwise what is wrong, for the user.
std::string editProblem(const SceneEdits& edits, const RenderSettings& settings);

// Index of the material / point light / triangular light with `id`, or -1.
int findMaterial(const SceneEdits& edits, const std::string& id);
int findPointLight(const SceneEdits& edits, const std::string& id);
int findTriangularLight(const SceneEdits& edits, const std::string& id);

}  // namespace rayview
