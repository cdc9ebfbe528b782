#pragma once
// Opening a model file (OBJ, PLY, STL, glTF and the other formats Assimp reads) as a scene: what the caller
// chooses, and which files are models. No Assimp here: rayview_import_client and rayview_import share it.

#include <filesystem>
#include <string>

namespace rayview {

enum class ModelUpAxis { Y, Z };

// Whose camera (or lights) a model is seen with: the file's when they show the model (it covers >= 5 % of the
// frame, in front of the camera, with enough light to see it by), else rayview's with a warning; the file's
// whatever they show; or rayview's own framing and light kit.
enum class ModelViewSource { FileWhenItShows, File, Rayview };

struct ModelImportOptions {
  ModelUpAxis up = ModelUpAxis::Y;  // which model axis points up in the made-up camera
  int width = 1280;                 // the made-up camera's image size (a file's own camera keeps this size too)
  int height = 720;
  ModelViewSource camera = ModelViewSource::FileWhenItShows;  // --camera file|auto
  ModelViewSource lights = ModelViewSource::FileWhenItShows;  // --lights file|kit
};

// A file Assimp 5.2.5 reads, by its extension (case-insensitive). A .xml file is never a model: it is the handout's
// scene format, even though Assimp reads some XML dialects.
bool isModelFile(const std::filesystem::path& path);

// "--up y|z" and "WxH" as the command line and the worker spell them; false when the text is not one.
bool parseModelUpAxis(const std::string& text, ModelUpAxis& up);
bool parseResolution(const std::string& text, int& width, int& height);
// "--camera file|auto" and "--lights file|kit" (and "shown", the default, for either); false for anything else.
bool parseModelCamera(const std::string& text, ModelViewSource& source);
bool parseModelLights(const std::string& text, ModelViewSource& source);
// The word each parser reads back: "shown", "file", then "auto" (camera) or "kit" (lights).
std::string modelCameraWord(ModelViewSource source);
std::string modelLightsWord(ModelViewSource source);

}  // namespace rayview
