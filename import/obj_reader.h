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

// One MTL material as written: its statements (key and the rest of the line, in order), turned into an Assimp
// material only when a mesh uses it (an aiMaterial costs about 1 KB a property, too much for 100 000 materials).
struct ObjMaterial {
  std::string name;
  std::vector<std::pair<std::string, std::string>> statements;
  bool defined = false;  // by an MTL's newmtl (not only named by a usemtl before its mtllib line)
};

// The materials an OBJ file's MTL libraries define, in order, and their index by name.
struct ObjMaterials {
  std::vector<ObjMaterial> list;
  std::unordered_map<std::string, unsigned> byName;
  // The index of a material of that name, added (with no statements: grey 0.6) when there is none.
  unsigned named(const std::string& name);
  // The index of Assimp's "DefaultMaterial" (grey 0.6, as Assimp's OBJ reader gives faces without usemtl).
  unsigned defaultMaterial();
  // An aiScene holding, for mapMaterials, the materials `used` marks as Assimp's OBJ reader would make them (the
  // others null).
  std::unique_ptr<aiScene> toScene(const std::vector<bool>& used) const;
};

// Where an MTL library named on an `mtllib` line is: beside the model.
std::filesystem::path materialLibraryPath(const std::filesystem::path& modelPath, const std::string& library);

// Parses an MTL file's text into `out` (newmtl and each material's statements; toScene reads Kd, Ka, Ks, Ke, Ns, Ni,
// d, Tr, Pr, Pm, map_Kd and the other maps as Assimp's OBJ reader does). A second definition of a name is ignored.
// A number of those keys that is not finite as a float (nan, inf, 1e39) throws SceneError at `file`'s line: it would
// otherwise surface as a value of the scene rayview makes up, which the user never wrote.
void parseMaterialLibrary(std::string_view text, ObjMaterials& out, const std::filesystem::path& file);

// Reads the OBJ file at `path` into `g` (each mesh's material an index into the returned list) and returns its
// materials. Throws SceneError naming the file and the line.
ObjMaterials readObj(const std::filesystem::path& path, SceneGeometry& g, Notes& notes);

// The materials the meshes use, as mapMaterials gives them for Assimp's OBJ materials (same ids, colours and
// texture). Without textures it computes them directly: 100 000 aiMaterials would take seconds and 300 MB.
void mapObjMaterials(const ObjMaterials& materials, const std::filesystem::path& path, Scene& out, Notes& notes);

}  // namespace rayview::model
