// MTL libraries as Assimp materials, with the keys and defaults Assimp's OBJ reader uses, so that mapMaterials
// (model_materials.cpp) treats a model read by rayview's OBJ reader as it treated one read by Assimp.

#include <assimp/material.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cmath>
#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <string>
#include <optional>

#include "obj_reader.h"
#include "rayview/diagnostics.h"
#include "rayview/metal_rough.h"

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

// A new material as Assimp's OBJ reader starts one: grey 0.6 diffuse. Its other defaults (no ambient, specular or
// emission, opaque, shininess 0) are what mapMaterials assumes when a key is absent, so they are not stored.
aiMaterial* newMaterial(const std::string& name) {
  auto* m = new aiMaterial;
  const aiString id(name);
  m->AddProperty(&id, AI_MATKEY_NAME);
  const aiColor3D grey(0.6f, 0.6f, 0.6f);
  m->AddProperty(&grey, 1, AI_MATKEY_COLOR_DIFFUSE);
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

unsigned ObjMaterials::named(const std::string& name) {
  const auto [it, added] = byName.try_emplace(name, static_cast<unsigned>(list.size()));
  if (added) list.push_back(ObjMaterial{name, {}});
  return it->second;
}

unsigned ObjMaterials::defaultMaterial() { return named(AI_DEFAULT_MATERIAL_NAME); }

std::unique_ptr<aiScene> ObjMaterials::toScene(const std::vector<bool>& used) const {
  auto scene = std::make_unique<aiScene>();
  scene->mNumMaterials = static_cast<unsigned>(list.size());
  scene->mMaterials = new aiMaterial*[list.size() + 1]();
  for (std::size_t i = 0; i < list.size(); ++i) {
    if (i >= used.size() || !used[i]) continue;
    aiMaterial* m = newMaterial(list[i].name);
    scene->mMaterials[i] = m;
    for (const auto& [key, rest] : list[i].statements) {
      if (const aiTextureType type = mapType(key); type != aiTextureType_NONE) {
        const aiString file(mapFile(rest));
        if (file.length > 0) m->AddProperty(&file, AI_MATKEY_TEXTURE(type, 0));
      } else {
        applyStatement(*m, key, rest);
      }
    }
  }
  return scene;
}

std::filesystem::path materialLibraryPath(const std::filesystem::path& modelPath, const std::string& library) {
  return modelPath.parent_path() / library;
}

namespace {

// The keys whose words are numbers (the spectral and xyz forms of a colour are skipped, their words too).
bool numericKey(std::string_view key) {
  for (const char* k : {"Kd", "Ka", "Ks", "Ke", "Ns", "Ni", "d", "Tr", "Pr", "Pm"})
    if (key == k) return true;
  return false;
}

// The first word of a numeric statement that reads as a number but not as a finite float ("" when none).
std::string_view unusableNumber(std::string_view rest) {
  for (std::string_view w = word(rest); !w.empty(); w = word(rest)) {
    std::string_view digits = w;
    if (digits[0] == '+') digits.remove_prefix(1);
    double v = 0.0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
    if (end != digits.data() + digits.size()) break;  // a word, not a number: "spectral", "xyz"
    // Out of a double's range: strtod says which way (HUGE_VAL over, 0 under; an underflow is a usable 0).
    if (error == std::errc::result_out_of_range) v = std::strtod(std::string(digits).c_str(), nullptr);
    if (!(std::abs(v) <= std::numeric_limits<float>::max())) return w;
  }
  return {};
}

}  // namespace

void parseMaterialLibrary(std::string_view text, ObjMaterials& out, const std::filesystem::path& file) {
  std::size_t current = SIZE_MAX;  // the material being defined, or none
  for (int lineNumber = 1; !text.empty(); ++lineNumber) {
    std::size_t end = text.find('\n');
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(0, end);
    text.remove_prefix(std::min(end + 1, text.size()));
    if (const std::size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    const std::string_view key = word(line);
    if (key.empty()) continue;
    if (numericKey(key))
      if (const std::string_view bad = unusableNumber(line); !bad.empty())
        throwSceneError(SourceLocation{file.string(), lineNumber},
                        std::string(key) + ": '" + std::string(bad) + "' is not a finite number rayview can use");
    if (key == "newmtl") {
      const std::string name(trimmed(line));
      const unsigned index = out.named(name);
      current = out.list[index].defined ? SIZE_MAX : index;  // a second definition of a name is ignored
      out.list[index].defined = true;
      continue;
    }
    if (current != SIZE_MAX) out.list[current].statements.emplace_back(std::string(key), std::string(trimmed(line)));
  }
}

namespace {

// What mapMaterials reads of an OBJ material (model_materials.cpp, phongOf), read from its statements.
struct PhongInputs {
  aiColor3D kd{0.6f, 0.6f, 0.6f};
  std::optional<aiColor3D> ks;
  std::optional<float> ns, pr, pm;
  bool textured = false;  // names a texture or an opacity map (a cut-out): mapMaterials keeps them
};

PhongInputs inputsOf(const ObjMaterial& m) {
  PhongInputs in;
  for (const auto& [key, rest] : m.statements) {
    std::string_view line = rest;
    if (const aiTextureType type = mapType(key); type == aiTextureType_DIFFUSE || type == aiTextureType_OPACITY)
      in.textured |= !mapFile(rest).empty();
    else if (key == "Kd") in.kd = colorOf(line).value_or(in.kd);
    else if (key == "Ks") in.ks = colorOf(line) ? colorOf(line) : in.ks;
    else if (key == "Ns") in.ns = number(word(line)) ? number(rest) : in.ns;
    else if (key == "Pr") in.pr = number(word(line)) ? number(rest) : in.pr;
    else if (key == "Pm") in.pm = number(word(line)) ? number(rest) : in.pm;
  }
  return in;
}

Color clamp01(const aiColor3D& c) { return glm::clamp(Color(c.r, c.g, c.b), Color(0.0f), Color(1.0f)); }

// What phongOf (model_materials.cpp) makes of the keys an OBJ material can have.
Material phongOf(const PhongInputs& in) {
  Material out;
  out.diffuse = clamp01(in.kd);
  if (in.pr || in.pm) {
    float metallic = in.pm.value_or(0.0f), roughness = in.pr.value_or(1.0f);
    metallic = std::clamp(std::isfinite(metallic) ? metallic : 0.0f, 0.0f, 1.0f);
    roughness = std::clamp(std::isfinite(roughness) ? roughness : 1.0f, 0.0f, 1.0f);
    setPhongTerms(out, metalRoughTerms(out.diffuse, metallic, roughness));
    return out;
  }
  if (in.ks) out.specular = clamp01(*in.ks);
  if (in.ns && std::isfinite(*in.ns) && *in.ns > 0.0f) out.phongExponent = std::clamp(*in.ns, 1.0f, 10000.0f);
  out.ambient = out.diffuse;
  return out;
}

}  // namespace

void mapObjMaterials(const ObjMaterials& materials, const std::filesystem::path& path, Scene& out, Notes& notes) {
  std::vector<bool> used(materials.list.size(), false);
  for (const Mesh& mesh : out.meshes) used[mesh.material] = true;
  std::vector<PhongInputs> inputs(materials.list.size());
  bool textured = false;
  for (std::size_t i = 0; i < inputs.size(); ++i)
    if (used[i]) textured |= (inputs[i] = inputsOf(materials.list[i])).textured;
  if (textured) {  // the texture's choice, loading and averaging are mapMaterials' alone
    mapMaterials(*materials.toScene(used), path, out, notes);
    return;
  }
  // As mapMaterials numbers and names them: in order of first use, repeated names given _2, _3, ...
  std::vector<std::int64_t> ours(materials.list.size(), -1);
  std::unordered_map<std::string, int> taken;
  for (Mesh& mesh : out.meshes) {
    std::int64_t& our = ours[mesh.material];
    if (our < 0) {
      our = static_cast<std::int64_t>(out.materials.size());
      Material material = phongOf(inputs[mesh.material]);
      material.id = materials.list[mesh.material].name;
      if (material.id.empty()) material.id = "material" + std::to_string(mesh.material + 1);
      if (const int seen = taken[material.id]++; seen > 0) material.id.append(1, '_').append(std::to_string(seen + 1));
      out.materials.push_back(std::move(material));
    }
    mesh.material = static_cast<std::uint32_t>(our);
  }
}

}  // namespace rayview::model
