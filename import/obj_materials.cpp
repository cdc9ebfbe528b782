// MTL libraries as Assimp materials, with the keys and defaults Assimp's OBJ reader uses, so that mapMaterials
// (model_materials.cpp) treats a model read by rayview's OBJ reader as it treated one read by Assimp.

#include <assimp/material.h>
#include <assimp/scene.h>

#include <algorithm>
#include <charconv>
#include <optional>

#include "obj_reader.h"

namespace rayview::model {
namespace {

bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && isBlank(s.front())) s.remove_prefix(1);
  while (!s.empty() && isBlank(s.back())) s.remove_suffix(1);
  return s;
}

// The next word of `s`, taken off its front.
std::string_view word(std::string_view& s) {
  s = trimmed(s);
  std::size_t n = 0;
  while (n < s.size() && !isBlank(s[n])) ++n;
  const std::string_view w = s.substr(0, n);
  s.remove_prefix(n);
  return w;
}

std::optional<float> number(std::string_view w) {
  if (!w.empty() && w[0] == '+') w.remove_prefix(1);
  float v = 0.0f;
  const auto [end, error] = std::from_chars(w.data(), w.data() + w.size(), v);
  if (w.empty() || error != std::errc() || end != w.data() + w.size()) return std::nullopt;
  return v;
}

// "Kd r g b" or "Kd r" (grey); nullopt for the spectral and xyz forms, which are skipped.
std::optional<aiColor3D> colorOf(std::string_view rest) {
  const auto r = number(word(rest));
  if (!r) return std::nullopt;
  const auto g = number(word(rest)), b = number(word(rest));
  if (!g || !b) return aiColor3D(*r, *r, *r);
  return aiColor3D(*r, *g, *b);
}

// A map line's file name: what follows the options ("-s 1 1 1", "-clamp on", "-bm 0.5", ...), spaces kept.
std::string mapFile(std::string_view rest) {
  rest = trimmed(rest);
  while (!rest.empty() && rest[0] == '-') {
    word(rest);  // the option
    for (std::string_view next = trimmed(rest); !next.empty();) {
      std::string_view probe = next;
      const std::string_view w = word(probe);
      const bool argument = number(w) || w == "on" || w == "off" || (w.size() == 1 && std::string_view("rgbmlz").find(w) != std::string_view::npos) ||
                            w == "sphere" || w == "cube_top" || w == "cube_bottom" || w == "cube_front" ||
                            w == "cube_back" || w == "cube_left" || w == "cube_right";
      if (!argument || probe.empty()) break;  // a last word is the file, whatever it looks like
      rest = probe;
      next = trimmed(rest);
    }
    rest = trimmed(rest);
  }
  return std::string(rest);
}

aiTextureType mapType(std::string_view key) {
  if (key == "map_Kd") return aiTextureType_DIFFUSE;
  if (key == "map_Ka") return aiTextureType_AMBIENT;
  if (key == "map_Ks") return aiTextureType_SPECULAR;
  if (key == "map_Ke") return aiTextureType_EMISSIVE;
  if (key == "map_d") return aiTextureType_OPACITY;
  if (key == "map_Ns") return aiTextureType_SHININESS;
  if (key == "map_bump" || key == "map_Bump" || key == "bump") return aiTextureType_HEIGHT;
  if (key == "disp") return aiTextureType_DISPLACEMENT;
  if (key == "refl") return aiTextureType_REFLECTION;
  return aiTextureType_NONE;
}

// A new material with Assimp's OBJ defaults: grey 0.6 diffuse, no ambient or specular, opaque.
aiMaterial* newMaterial(const std::string& name) {
  auto* m = new aiMaterial;
  const aiString id(name);
  m->AddProperty(&id, AI_MATKEY_NAME);
  const aiColor3D grey(0.6f, 0.6f, 0.6f), black(0.0f, 0.0f, 0.0f);
  m->AddProperty(&grey, 1, AI_MATKEY_COLOR_DIFFUSE);
  m->AddProperty(&black, 1, AI_MATKEY_COLOR_AMBIENT);
  m->AddProperty(&black, 1, AI_MATKEY_COLOR_SPECULAR);
  m->AddProperty(&black, 1, AI_MATKEY_COLOR_EMISSIVE);
  const float one = 1.0f, zero = 0.0f;
  m->AddProperty(&one, 1, AI_MATKEY_OPACITY);
  m->AddProperty(&zero, 1, AI_MATKEY_SHININESS);
  return m;
}

// One MTL statement on the current material (AddProperty replaces an earlier value of the same key).
void applyStatement(aiMaterial& m, std::string_view key, std::string_view rest) {
  if (key == "Kd" || key == "Ka" || key == "Ks" || key == "Ke") {
    const auto c = colorOf(rest);
    if (!c) return;
    if (key == "Kd") m.AddProperty(&*c, 1, AI_MATKEY_COLOR_DIFFUSE);
    if (key == "Ka") m.AddProperty(&*c, 1, AI_MATKEY_COLOR_AMBIENT);
    if (key == "Ks") m.AddProperty(&*c, 1, AI_MATKEY_COLOR_SPECULAR);
    if (key == "Ke") m.AddProperty(&*c, 1, AI_MATKEY_COLOR_EMISSIVE);
    return;
  }
  const std::optional<float> value = number(word(rest));
  if (key == "Ns" && value) m.AddProperty(&*value, 1, AI_MATKEY_SHININESS);
  else if (key == "Ni" && value) m.AddProperty(&*value, 1, AI_MATKEY_REFRACTI);
  else if (key == "d" && value) m.AddProperty(&*value, 1, AI_MATKEY_OPACITY);
  else if (key == "Tr" && value) {
    const float opacity = 1.0f - *value;
    m.AddProperty(&opacity, 1, AI_MATKEY_OPACITY);
  } else if (key == "Pr" && value) m.AddProperty(&*value, 1, AI_MATKEY_ROUGHNESS_FACTOR);
  else if (key == "Pm" && value) m.AddProperty(&*value, 1, AI_MATKEY_METALLIC_FACTOR);
}

}  // namespace

ObjMaterials::~ObjMaterials() {
  for (aiMaterial* m : list) delete m;
}

unsigned ObjMaterials::defaultMaterial() {
  const auto [it, added] = byName.emplace(AI_DEFAULT_MATERIAL_NAME, static_cast<unsigned>(list.size()));
  if (added) list.push_back(newMaterial(AI_DEFAULT_MATERIAL_NAME));
  return it->second;
}

std::unique_ptr<aiScene> ObjMaterials::takeInto() {
  auto scene = std::make_unique<aiScene>();
  scene->mNumMaterials = static_cast<unsigned>(list.size());
  scene->mMaterials = new aiMaterial*[list.size() + 1];
  for (std::size_t i = 0; i < list.size(); ++i) scene->mMaterials[i] = list[i];
  list.clear();
  byName.clear();
  return scene;
}

std::filesystem::path materialLibraryPath(const std::filesystem::path& modelPath, const std::string& library) {
  return modelPath.parent_path() / library;
}

void parseMaterialLibrary(std::string_view text, ObjMaterials& out) {
  aiMaterial* current = nullptr;
  while (!text.empty()) {
    std::size_t end = text.find('\n');
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(0, end);
    text.remove_prefix(std::min(end + 1, text.size()));
    if (const std::size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    const std::string_view key = word(line);
    if (key.empty()) continue;
    if (key == "newmtl") {
      const std::string name(trimmed(line));
      const auto [it, added] = out.byName.emplace(name, static_cast<unsigned>(out.list.size()));
      current = added ? newMaterial(name) : nullptr;  // a second definition of a name is ignored
      if (added) out.list.push_back(current);
      continue;
    }
    if (!current) continue;
    if (const aiTextureType type = mapType(key); type != aiTextureType_NONE) {
      const aiString file(mapFile(line));
      if (file.length > 0) current->AddProperty(&file, AI_MATKEY_TEXTURE(type, 0));
      continue;
    }
    applyStatement(*current, key, line);
  }
}

}  // namespace rayview::model
