#include <algorithm>
#include <iterator>
#include <cctype>
#include <charconv>
#include <string_view>

#include "rayview/model_options.h"

namespace rayview {
namespace {

// Assimp 5.2.5's importers by extension (Importer::GetExtensionList), less .xml and .mesh.xml: a .xml is the
// handout's scene format.
constexpr std::string_view kModelExtensions[] = {
    "3d",  "3ds",    "3mf", "ac",   "ac3d", "acc",    "amf",   "ase",   "ask",     "assbin", "b3d", "blend", "bsp",
    "bvh", "cob",    "csm", "dae",  "dxf",  "enff",   "fbx",   "glb",   "gltf",    "hmp",    "ifc", "ifczip", "iqm",
    "irr", "irrmesh", "lwo", "lws", "lxo",  "md2",    "md3",   "md5anim", "md5camera", "md5mesh", "mdc", "mdl",
    "mesh", "mot",   "ms3d", "ndo", "nff",  "obj",    "off",   "ogex",  "pk3",     "ply",    "pmx", "prj",   "q3o",
    "q3s", "raw",    "scn", "sib",  "smd",  "step",   "stl",   "stp",   "ter",     "uc",     "vta", "x",     "x3d",
    "x3db", "xgl",   "zae", "zgl"};

std::string lowered(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  return text;
}

bool parsePositive(std::string_view text, int& value) {
  const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
  return result.ec == std::errc() && result.ptr == text.data() + text.size() && value > 0;
}

}  // namespace

bool isModelFile(const std::filesystem::path& path) {
  std::string extension = lowered(path.extension().string());
  if (extension.size() < 2) return false;
  extension.erase(0, 1);
  return std::find(std::begin(kModelExtensions), std::end(kModelExtensions), extension) != std::end(kModelExtensions);
}

bool parseModelUpAxis(const std::string& text, ModelUpAxis& up) {
  const std::string axis = lowered(text);
  if (axis == "y") up = ModelUpAxis::Y;
  else if (axis == "z") up = ModelUpAxis::Z;
  else return false;
  return true;
}

bool parseResolution(const std::string& text, int& width, int& height) {
  const std::size_t x = text.find_first_of("xX");
  if (x == std::string::npos) return false;
  int w = 0, h = 0;
  if (!parsePositive(std::string_view(text).substr(0, x), w) || !parsePositive(std::string_view(text).substr(x + 1), h))
    return false;
  if (w > 32768 || h > 32768) return false;
  width = w;
  height = h;
  return true;
}

}  // namespace rayview
