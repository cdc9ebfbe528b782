#pragma once
// What an edit of the scene's parameters costs, and whether they can be rendered. The viewer edits a
// SceneParameters (camera, lights, materials, depth, background): geometry is not editable, so an edit never
// needs a new BVH; it only needs a new parameter snapshot and a render restart.

#include <string>
#include <string_view>
#include <vector>

#include "rayview/render_settings.h"
#include "rayview/scene.h"

namespace rayview {

// Largest image the viewer renders (each side, and in total), so a typo in a field cannot exhaust memory.
inline constexpr int kMaxViewerImageSide = 16384;
inline constexpr long long kMaxViewerImagePixels = 64LL * 1024 * 1024;

enum class EditEffect {
  None,     // nothing the image depends on changed (or only display settings)
  Restart,  // new snapshot + restart on the same geometry
  Rebuild,  // another traversal back-end: the geometry must be prepared again
};

EditEffect classifyEdit(const SceneParameters& before, const RenderSettings& beforeSettings,
                        const SceneParameters& after, const RenderSettings& afterSettings);

// Empty when the parameters describe a scene that can be rendered; otherwise what is wrong, for the user.
std::string editProblem(const SceneParameters& edits, const RenderSettings& settings);

// The same but for where the camera stands and looks (position, gaze, up: what orbit, pan and dolly move).
// Moving the view is looking at the scene, not editing it: alone it never asks to be saved.
bool sameApartFromTheView(const SceneParameters& a, const SceneParameters& b);

// Index of the material with `id`, or -1.
int findMaterial(const SceneParameters& edits, const std::string& id);

}  // namespace rayview
