// Reading a model: rayview's own PLY/STL readers or Assimp, then materials, texture, camera and lights.

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <system_error>

#include "guarded_io.h"
#include "model_parts.h"
#include "rayview/model_import.h"

namespace rayview {
namespace {

namespace fs = std::filesystem;

constexpr unsigned kAssimpSteps = aiProcess_Triangulate | aiProcess_ValidateDataStructure;

void checkReadable(const fs::path& path) {
  std::error_code ec;
  const auto status = fs::status(path, ec);
  if (!fs::exists(status)) model::fail(path, "no such file");
  if (!fs::is_regular_file(status)) model::fail(path, "is not a regular file");
  if (fs::file_size(path, ec) == 0) model::fail(path, "is empty");
}

const aiScene* readWithAssimp(Assimp::Importer& importer, const fs::path& path) {
  auto* io = new model::GuardedIOSystem;  // the importer owns it
  importer.SetIOHandler(io);
  const aiScene* scene = importer.ReadFile(path.string(), kAssimpSteps);
  if (!io->refused().empty())
    model::fail(path, "names \"" + io->refused() + "\", which is not a regular file (a FIFO, socket or device is "
                      "never read)");
  if (!scene) {
    std::string why = importer.GetErrorString();
    model::fail(path, "cannot be read as a model" + (why.empty() ? std::string() : ": " + why));
  }
  if (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) model::fail(path, "cannot be read as a model (incomplete)");
  return scene;
}

std::string joined(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& item : items) out += (out.empty() ? "" : ", ") + item;
  return out.empty() ? "nothing" : out;
}

std::string counted(std::size_t count, const char* one, const char* many) {
  return std::to_string(count) + " " + (count == 1 ? one : many);
}

std::string summaryOf(const Scene& scene, const model::Notes& notes) {
  return counted(scene.triangles.size(), "triangle", "triangles") + ", " + counted(scene.meshes.size(), "mesh", "meshes") +
         ", " + counted(scene.materials.size(), "material", "materials") + ", texture " + notes.texture +
         "; made up: " + joined(notes.madeUp) + "; dropped: " + joined(notes.dropped);
}

// A PLY/STL read by rayview's own reader has one mesh and no materials: one made-up material.
void singleMaterial(Scene& scene, model::Notes& notes) {
  Material m;
  m.id = "material1";
  m.diffuse = m.ambient = Color(0.8f);
  m.specular = Color(0.2f);
  m.phongExponent = 32.0f;
  scene.materials.push_back(m);
  for (Mesh& mesh : scene.meshes) mesh.material = 0;
  notes.madeUp.push_back("material");
}

}  // namespace

SceneGeometry readModelGeometry(const fs::path& path, bool viaAssimp) {
  checkReadable(path);
  SceneGeometry geometry;
  model::Notes notes;
  if (!viaAssimp && model::readPlyOrStl(path, geometry, notes)) return geometry;
  Assimp::Importer importer;
  model::gatherGeometry(*readWithAssimp(importer, path), path, geometry, notes);
  return geometry;
}

ModelScene readModel(const fs::path& path, const ModelImportOptions& options) {
  checkReadable(path);
  ModelScene result;
  Scene& scene = result.scene;
  model::Notes notes;
  Assimp::Importer importer;
  const aiScene* assimp = nullptr;
  if (model::readPlyOrStl(path, scene, notes)) {
    singleMaterial(scene, notes);
  } else {
    assimp = readWithAssimp(importer, path);
    model::gatherGeometry(*assimp, path, scene, notes);
    model::mapMaterials(*assimp, path, scene, notes);
  }
  scene.sourcePath = path;
  model::frameScene(assimp, options, scene, notes);
  result.warnings = std::move(notes.warnings);
  result.summary = summaryOf(scene, notes);
  return result;
}

}  // namespace rayview
