#pragma once
// Saving under a new numbered name next to the scene (scene_001.png, scene_002.png, ...), never
// overwriting anything and never leaving a partial file under the final name.

#include <filesystem>
#include <functional>
#include <string>

#include "display_mapping.h"
#include "rayview/image.h"
#include "rayview/scene.h"

namespace rayview {

inline constexpr int kMaxNumberedFiles = 9999;

// Where numbered files for the scene at `scenePath` go: its directory, or the current directory for the
// embedded default scene ("" path), with the scene's stem ("default" for the embedded scene).
std::filesystem::path numberedFileBase(const std::string& scenePath);

// Writes through `write(temporaryPath)` and then claims `<base>_NNN<extension>` with the first free NNN.
// The claim is a hard link, which fails rather than replaces when the name exists, so a file that
// appeared meanwhile is never overwritten. Returns the final path; throws ImageIoError.
std::filesystem::path writeNumberedFile(const std::filesystem::path& base, const std::string& extension,
                                        const std::function<void(const std::filesystem::path&)>& write);

// Ctrl+S: the final pass as a PNG, scene_NNN.png; saved as displayed (exposure and gamma applied), it is
// scene_displayed_NNN.png, so that it is never taken for the render itself. Ctrl+Shift+S: the edited scene as XML.
std::filesystem::path saveFrameNumbered(const Image& image, const std::string& scenePath,
                                        FrameSave what = FrameSave::Raw);
std::filesystem::path saveSceneNumbered(const SceneParameters& parameters, const Scene& loaded,
                                        const std::string& scenePath);

// `path` for a save the user named, when writing it replaces nothing the open scene (`loaded`, read from
// `scenePath`) or the viewer read: the scene, its texture (loaded or not), the reference, the script. Else throws
// ImageIoError saying which input it is.
const std::string& refusingInputs(const std::string& path, const std::string& scenePath, const Scene* loaded);

}  // namespace rayview
