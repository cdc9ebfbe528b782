// Reading a model: rayview's own PLY/STL/OBJ readers or Assimp, then materials, texture, camera and lights.

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cctype>
#include <memory>
#include <system_error>

#include "assimp_warnings.h"
#include "guarded_io.h"
#include "model_parts.h"
#include "obj_reader.h"
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
  const model::AssimpWarnings warnings;
  auto* io = new model::GuardedIOSystem;  // the importer owns it
  importer.SetIOHandler(io);
  const aiScene* scene = importer.ReadFile(path.string(), kAssimpSteps);
  if (!io->refused().empty())
    model::fail(path, "names \"" + io->refused() + "\", which is not a regular file (a FIFO, socket or device is "
                      "never read)");
  if (const std::string broken = warnings.brokenData(); !broken.empty())
    model::fail(path, "is broken (" + broken + "); rayview refuses it rather than draw what is left");
  if (!scene) {
    std::string why = importer.GetErrorString();
    model::fail(path, "cannot be read as a model" + (why.empty() ? std::string() : ": " + why));
  }
  if (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) model::fail(path, "cannot be read as a model (incomplete)");
  return scene;
}

// OBJ files are read by rayview's own reader (obj_reader.h): exact numbers, shared vertices, checked indices.
bool isObj(const fs::path& path) {
  std::string extension = path.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension == ".obj";
}

std::string joined(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& item : items) out += (out.empty() ? "" : ", ") + item;
  return out.empty() ? "nothing" : out;
}

std::string counted(std::size_t count, const char* one, const char* many) {
  return std::to_string(count) + " " + (count == 1 ? one : many);
}

// ", texture NAME (WxH)", ", textures A (WxH), B (WxH)" or ", texture none".
std::string textures(const model::Notes& notes) {
  if (notes.textures.empty()) return ", texture none";
  return (notes.textures.size() == 1 ? ", texture " : ", textures ") + joined(notes.textures);
}

std::string summaryOf(const Scene& scene, const model::Notes& notes) {
  return counted(scene.triangles.size(), "triangle", "triangles") + ", " + counted(scene.meshes.size(), "mesh", "meshes") +
         ", " + counted(scene.materials.size(), "material", "materials") + textures(notes) +
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
  if (!viaAssimp && isObj(path)) {
    model::readObj(path, geometry, notes);
    return geometry;
  }
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
  } else if (isObj(path)) {
    model::mapObjMaterials(model::readObj(path, scene, notes), path, scene, notes);
  } else {
    assimp = readWithAssimp(importer, path);
    model::gatherGeometry(*assimp, path, scene, notes);
    model::mapMaterials(*assimp, path, scene, notes);
  }
  // Both sides lit, as F3D and Blender light a model: whatever reader made them, a model's faces are often wound
  // inward (STL, PLY, OBJ exported from CAD).
  for (Material& m : scene.materials) m.twoSided = true;
  scene.sourcePath = path;
  model::frameScene(assimp, options, scene, notes);
  result.warnings = std::move(notes.warnings);
  result.summary = summaryOf(scene, notes);
  return result;
}

}  // namespace rayview
