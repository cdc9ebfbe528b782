// Which files rayview reads itself rather than through Assimp: PLY (with the renderer's reader, which the CENG477
// dialect's <Faces plyFile> uses too) and STL, by extension (faster than Assimp's readers, docs/dependencies.md,
// and they take files Assimp refuses, such as a PLY header after a blank line).

#include <algorithm>
#include <cmath>
#include <string_view>

#include "byte_input.h"
#include "model_parts.h"
#include "rayview/file_names.h"
#include "rayview/ply_reader.h"

namespace rayview::model {
namespace {

// A file's normal as a unit vector; +z for one of no length or not finite.
glm::vec3 unitNormal(const glm::vec3& n) {
  const float length = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
  return length > 0.0f && std::isfinite(length) ? n / length : glm::vec3(0.0f, 0.0f, 1.0f);
}

// The renderer's PLY reader (renderer/ply_reader.h) into one mesh; each corner's normal and texture coordinate are
// its vertex's.
void readPly(const std::string& bytes, const std::filesystem::path& path, SceneGeometry& g, Notes& notes) {
  detail::PlyMesh ply;
  try {
    ply = detail::parsePly(bytes);
  } catch (const detail::PlyError& error) {
    fail(path, error.message);
  }
  if (ply.triangles.empty()) fail(path, "the file has no triangles");
  if (ply.skippedFaces > 0) notes.dropped.push_back(std::to_string(ply.skippedFaces) + " faces of fewer than 3 vertices");
  if (!ply.colors.empty() && ply.colors.size() == ply.vertices.size()) {
    g.vertexColors.reserve(ply.colors.size());
    for (const glm::vec3& c : ply.colors)  // float colours may stray outside 0..1
      g.vertexColors.push_back(glm::clamp(glm::vec3(std::isfinite(c.x) ? c.x : 1.0f, std::isfinite(c.y) ? c.y : 1.0f,
                                                    std::isfinite(c.z) ? c.z : 1.0f), 0.0f, 1.0f));
  }
  g.vertices = std::move(ply.vertices);
  g.normals.resize(ply.normals.size());
  std::transform(ply.normals.begin(), ply.normals.end(), g.normals.begin(), unitNormal);
  g.texCoords = std::move(ply.texCoords);
  g.triangles = std::move(ply.triangles);
  if (!g.normals.empty() || !g.texCoords.empty()) {
    g.faceAttributes.resize(g.triangles.size());
    for (std::size_t i = 0; i < g.triangles.size(); ++i)
      for (int c = 0; c < 3; ++c) {
        const auto vertex = static_cast<std::int32_t>(g.triangles[i].vertex[c]);
        if (!g.normals.empty()) g.faceAttributes[i].normal[c] = vertex;
        if (!g.texCoords.empty()) g.faceAttributes[i].texCoord[c] = vertex;
      }
  }
  g.meshes.push_back(Mesh{path.stem().string(), 0, 0, static_cast<std::uint32_t>(g.triangles.size())});
}

}  // namespace

bool readPlyOrStl(const std::filesystem::path& path, SceneGeometry& geometry, Notes& notes) {
  const std::string extension = lowerExtension(path);
  if (extension != ".ply" && extension != ".stl") return false;
  std::string problem;
  const std::string bytes = readWholeFile(path, problem);
  if (!problem.empty()) fail(path, problem);
  if (extension == ".ply") readPly(bytes, path, geometry, notes);
  else readStl(bytes, path, geometry);
  return true;
}

}  // namespace rayview::model
