#pragma once
// The steps of reading a model (private to rayview_import): geometry from Assimp's scene, the materials and the
// texture, the made-up camera and lights.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "rayview/model_options.h"
#include "rayview/scene.h"

struct aiScene;

namespace rayview::model {

// What the summary line reports.
struct Notes {
  std::vector<std::string> madeUp;
  std::vector<std::string> dropped;
  std::vector<std::string> warnings;
  std::vector<std::string> textures;  // each kept texture: its file name and size
};

struct Bounds {
  glm::dvec3 lo{0.0}, hi{0.0};
  bool empty = true;
};
Bounds boundsOf(const SceneArray<glm::dvec3>& vertices);

// Assimp's meshes as instanced by its node tree, transformed to world space. Each Mesh's `material` is Assimp's
// material index until mapMaterials renumbers it. Throws SceneError for non-finite vertices, bad indices, too much.
void gatherGeometry(const aiScene& scene, const std::filesystem::path& path, SceneGeometry& geometry, Notes& notes);

// Each material the meshes use, in order of first use (mesh indices renumbered), each with its texture.
void mapMaterials(const aiScene& scene, const std::filesystem::path& path, Scene& out, Notes& notes);

// The file's own camera and lights when it has them (glTF, FBX, COLLADA), else made up from the bounds.
void frameScene(const aiScene* scene, const ModelImportOptions& options, Scene& out, Notes& notes);

// The share (0..1) of the camera's frame that the model's triangles cover, on a coarse grid; 0 when the camera is
// inside the model's bounding box or every triangle is behind it.
double frameCoverage(const Camera& camera, const SceneGeometry& geometry, const Bounds& bounds);
// The lights' mean irradiance (0..255 scale) at the model's centre, no light counted nearer than `radius`.
float irradianceAt(const std::vector<PointLight>& lights, const glm::dvec3& centre, double radius);

// rayview's own readers: nullopt-like false when the file is not one they read (Assimp then reads it).
bool readPlyOrStl(const std::filesystem::path& path, SceneGeometry& geometry, Notes& notes);

// rayview's STL reader (ASCII and binary), for readPlyOrStl: false when `bytes` are not an STL file.
bool readStl(const std::string& bytes, const std::filesystem::path& path, SceneGeometry& geometry);

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& message);

// A texture's mean texel, each channel in [0, 1]: what the importer multiplies a textured material's colour by, and
// the exporter divides it by again.
Color averageOf(const Texture& texture);

}  // namespace rayview::model
