#include "rayview/scene.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <string_view>
#include <type_traits>
#include <unordered_set>

#include "rayview/accel.h"
#include "rayview/camera_rays.h"
#include "rayview/image_limits.h"

namespace rayview {

bool SceneParameters::hasMirrors() const {
  if (maxRayDepth <= 0) return false;
  for (const Material& m : materials)
    if (m.isMirror()) return true;
  return false;
}

std::uint32_t SceneGeometry::meshOf(std::uint32_t triangle) const {
  return static_cast<std::uint32_t>(
      lastRangeAtOrBefore(meshes.size(), triangle, [&](std::size_t k) { return meshes[k].firstTriangle; }));
}

std::string wholenessProblem(const Scene& s) {
  std::uint64_t next = 0;
  for (std::uint32_t m = 0; m < s.meshes.size(); ++m) {
    const Mesh& mesh = s.meshes[m];
    if (mesh.firstTriangle != next) return "mesh " + mesh.id + " does not start where the one before it ends";
    if (mesh.material >= s.materials.size()) return "mesh " + mesh.id + " has no real material";
    next += mesh.triangleCount;
    if (next > s.triangles.size()) return "mesh " + mesh.id + " claims more triangles than there are";
    for (std::uint32_t t = mesh.firstTriangle; t < next; ++t)
      if (s.meshOf(t) != m) return "meshOf(" + std::to_string(t) + ") is not mesh " + mesh.id;
  }
  if (next != s.triangles.size()) return "the meshes do not cover the triangles";
  if (!s.faceAttributes.empty() && s.faceAttributes.size() != s.triangles.size())
    return "face attributes are not one per triangle";
  if (!s.vertexColors.empty() && s.vertexColors.size() != s.vertices.size())
    return "vertex colours are not one per vertex";
  for (std::size_t i = 0; i < s.triangles.size(); ++i) {
    const FaceAttributes& a = s.attributesOf(i);
    for (int k = 0; k < 3; ++k) {
      if (s.triangles[i].vertex[k] >= s.vertices.size()) return "triangle " + std::to_string(i) + ": a vertex out of range";
      if (a.hasTexCoords() && static_cast<std::size_t>(a.texCoord[k]) >= s.texCoords.size())
        return "triangle " + std::to_string(i) + ": a texture coordinate out of range";
      if (a.hasNormals() && static_cast<std::size_t>(a.normal[k]) >= s.normals.size())
        return "triangle " + std::to_string(i) + ": a normal out of range";
    }
  }
  return "";
}

namespace {

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool finite(const Color& c) { return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z); }

std::string cameraValuesProblem(const Camera& c) {
  if (!finite(c.position) || !finite(c.gaze) || !finite(c.up) || !std::isfinite(c.left) || !std::isfinite(c.right) ||
      !std::isfinite(c.bottom) || !std::isfinite(c.top) || !std::isfinite(c.nearDistance))
    return "the camera has a value that is not finite";
  if (std::string problem = cameraProblem(c); !problem.empty()) return "camera: " + problem;
  return imageSizeProblem(c.width, c.height);
}

std::string materialProblem(const Material& m) {
  if (!finite(m.ambient) || !finite(m.diffuse) || !finite(m.specular) || !finite(m.mirror) ||
      !std::isfinite(m.phongExponent) || !std::isfinite(m.textureFactor))
    return "material \"" + m.id + "\" has a value that is not finite";
  if (m.phongExponent < 0.0f) return "material \"" + m.id + "\" has a negative Phong exponent";
  if (!(m.alphaCutoff >= 0.0f && m.alphaCutoff <= 1.0f))
    return "material \"" + m.id + "\" has an alpha cutoff outside 0..1";
  return "";
}

}  // namespace

std::string parametersProblem(const SceneParameters& p) {
  if (p.maxRayDepth < 0 || p.maxRayDepth > kMaxRayDepth) return "the ray depth is out of range";
  if (!finite(p.background) || !finite(p.ambientLight)) return "the background or ambient light is not finite";
  if (p.shadowRayEpsilon && !(*p.shadowRayEpsilon >= 0.0 && *p.shadowRayEpsilon <= kEmbreeCoordinateLimit))
    return "the shadow-ray epsilon is out of range";
  if (std::string problem = cameraValuesProblem(p.camera); !problem.empty()) return problem;
  std::string problem;
  p.lights.forEachType([&](const auto& list) {
    for (const auto& light : list)
      for (const auto& field : std::remove_cvref_t<decltype(light)>::fields())
        if (problem.empty() && ((field.point && !finite(light.*field.point)) ||
                                (field.intensity && !finite(light.*field.intensity))))
          problem = "light \"" + light.id + "\" has a value that is not finite";
  });
  if (!problem.empty()) return problem;
  std::unordered_set<std::string_view> ids;
  for (const Material& m : p.materials) {
    if (std::string bad = materialProblem(m); !bad.empty()) return bad;
    if (!ids.insert(m.id).second) return "material id \"" + m.id + "\" is used twice";
  }
  return "";
}

void appendFace(SceneArray<Triangle>& triangles, std::vector<FaceAttributes>& faceAttributes, const Triangle& triangle,
                const FaceAttributes& attributes) {
  if (attributes.any() || !faceAttributes.empty()) {
    // Room for as many as the triangles have (the loader reserves those from the text's size): no reallocation.
    if (faceAttributes.empty()) faceAttributes.reserve(std::max(triangles.capacity(), triangles.size() + 1));
    faceAttributes.resize(triangles.size());  // the plain faces before the first with attributes: none
    faceAttributes.push_back(attributes);
  }
  triangles.push_back(triangle);
}

void SceneGeometry::addFace(const Triangle& triangle, const FaceAttributes& attributes) {
  appendFace(triangles, faceAttributes, triangle, attributes);
}

const Texture* SceneGeometry::textureOf(const Material& material) const {
  if (!material.textureImage.empty()) return textureNamed(material.textureImage);
  return texture && !texture->rgb.empty() ? &*texture : nullptr;
}

const Texture* SceneGeometry::textureNamed(const std::string& name) const {
  const auto named = std::find_if(materialTextures.begin(), materialTextures.end(),
                                  [&](const NamedTexture& t) { return t.name == name; });
  if (name.empty() || named == materialTextures.end() || !named->image || named->image->rgb.empty()) return nullptr;
  return &*named->image;
}

bool SceneGeometry::hasAnyTexture() const {
  return (texture && !texture->rgb.empty()) ||
         std::any_of(materialTextures.begin(), materialTextures.end(),
                     [](const NamedTexture& t) { return t.image && !t.image->rgb.empty(); });
}

}  // namespace rayview
