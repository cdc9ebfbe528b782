#pragma once
// rayview's own OBJ and MTL reader (private to rayview_import). Numbers are read correctly rounded
// (std::from_chars), the file's vertices, normals and texture coordinates stay shared as the file shares them, every
// index is checked with its line, and each run of faces under one group/object and material is a mesh.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "model_parts.h"

struct aiMaterial;
struct aiScene;

namespace rayview::model {

// The materials an OBJ file's MTL libraries define, in order, and their index by name.
struct ObjMaterials {
  std::vector<aiMaterial*> list;  // owned until handed to an aiScene (takeInto)
  std::unordered_map<std::string, unsigned> byName;
  ObjMaterials() = default;
  ObjMaterials(const ObjMaterials&) = delete;
  ObjMaterials& operator=(const ObjMaterials&) = delete;
  ~ObjMaterials();
  // The index of Assimp's "DefaultMaterial" (grey 0.6, as Assimp's OBJ reader gives faces without usemtl).
  unsigned defaultMaterial();
  // An aiScene holding only the materials, for mapMaterials; the list is left empty.
  std::unique_ptr<aiScene> takeInto();
};

// Where an MTL library named on an `mtllib` line is: beside the model.
std::filesystem::path materialLibraryPath(const std::filesystem::path& modelPath, const std::string& library);

// Parses an MTL file's text into `out` (newmtl, Kd, Ka, Ks, Ke, Ns, Ni, d, Tr, Pr, Pm, map_Kd and the other maps, as
// Assimp's OBJ reader sets them). Later definitions of a name already defined are ignored.
void parseMaterialLibrary(std::string_view text, ObjMaterials& out);

// Reads the OBJ file at `path` into `g` (each mesh's material an index into the returned scene's materials) and
// returns its materials as an aiScene of materials only. Throws SceneError naming the file and the line.
std::unique_ptr<aiScene> readObj(const std::filesystem::path& path, SceneGeometry& g, Notes& notes);

}  // namespace rayview::model
