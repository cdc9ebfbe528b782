#pragma once
// Writing a Scene back in the handout's XML format ("Save scene as" in the viewer).
//
// Correct spellings only (<background>, <nearplane>, <intensity>, <triangularlight>, <mirrorreflectance>),
// every number in the shortest text that reads back to the same value, faces 1-based, written v/t/n when
// a face has texture coordinates or normals. Loading the file back gives a Scene equal field by field,
// so it renders the same image.

#include <filesystem>
#include <string>

#include "rayview/scene.h"

namespace rayview {

// How doubles are written: the shortest text that reads back as the same double, or, for files other tools read
// as float (an imported model's scene), the float's text (at most 9 significant digits) when the double is exactly a
// float.
enum class NumberText { Shortest, FloatWhenExact };

// The whole file. `textureImage` is what to write in <textureimage> (nothing is written when empty).
std::string sceneToXml(const SceneParameters& parameters, const SceneGeometry& geometry, const std::string& textureImage,
                       NumberText style = NumberText::Shortest);
std::string sceneToXml(const Scene& scene, const std::string& textureImage);

// What <textureimage> must say in a file written to `outputPath` so that it still finds the image the
// scene was loaded with: unchanged in the scene's own directory, else a path to the file that was found.
// The same for any image name the scene's file gives (a material's own <textureimage>).
std::string textureReferenceFor(const Scene& scene, const std::filesystem::path& outputPath);
std::string textureReferenceFor(const Scene& scene, const std::string& name, const std::filesystem::path& outputPath);

// Writes the file whole (temporary file + rename). Throws ImageIoError (the file-writing error type) when the name
// does not end in .xml, or is a file the scene or the process read (outputOverwritesInput): the scene, its texture.
// `parameters` (the viewer's edits) over the geometry of `loaded`, the scene as it was read (its texture is
// found relative to the file it came from): no copy of the meshes.
void writeSceneFile(const std::filesystem::path& outputPath, const SceneParameters& parameters, const Scene& loaded);
void writeSceneFile(const std::filesystem::path& outputPath, const Scene& scene);

// Shortest decimal text that parses (as a double, as the loader does) back to exactly `value`.
std::string formatNumber(double value);
std::string formatNumber(float value);

}  // namespace rayview
