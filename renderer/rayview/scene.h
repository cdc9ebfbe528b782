#pragma once
// The scene as plain arrays, exactly what a file describes (SPEC sections 2-5). No acceleration data, no GL.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace rayview {

// Radiance and colours are in the file's 0..255 units.
using Color = glm::vec3;

struct Camera {
  glm::dvec3 position{0.0};
  glm::dvec3 gaze{0.0, 0.0, -1.0};
  glm::dvec3 up{0.0, 1.0, 0.0};
  double left = -1.0, right = 1.0, bottom = -1.0, top = 1.0;  // <nearplane> l r b t
  double nearDistance = 1.0;
  int width = 0;   // <imageresolution> nx
  int height = 0;  // <imageresolution> ny
};

struct PointLight {
  std::string id;
  glm::dvec3 position{0.0};
  Color intensity{0.0f};
};

struct TriangularLight {
  std::string id;
  glm::dvec3 vertex1{0.0}, vertex2{0.0}, vertex3{0.0};
  Color intensity{0.0f};
};

struct Material {
  std::string id;
  Color ambient{0.0f}, diffuse{0.0f}, specular{0.0f};
  float phongExponent = 1.0f;
  Color mirror{0.0f};         // <mirrorreflectance>
  float textureFactor = 0.0f;  // <texturefactor>, 2025 variant

  bool isMirror() const { return mirror.x != 0.0f || mirror.y != 0.0f || mirror.z != 0.0f; }
};

inline constexpr std::int32_t kNoIndex = -1;

// One face, already resolved to 0-based indices into the scene's arrays.
struct Triangle {
  std::uint32_t vertex[3] = {0, 0, 0};
  std::int32_t texCoord[3] = {kNoIndex, kNoIndex, kNoIndex};  // into Scene::texCoords
  std::int32_t normal[3] = {kNoIndex, kNoIndex, kNoIndex};    // into Scene::normals
  std::uint32_t material = 0;                                 // into Scene::materials
  std::uint32_t mesh = 0;                                     // into Scene::meshes

  bool hasTexCoords() const { return texCoord[0] != kNoIndex; }
  bool hasNormals() const { return normal[0] != kNoIndex; }
};

struct Mesh {
  std::string id;
  std::uint32_t material = 0;
  std::uint32_t firstTriangle = 0;
  std::uint32_t triangleCount = 0;
};

// 8-bit RGB texture, rows top to bottom as stored in the image file.
struct Texture {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;
};

struct Scene {
  int maxRayDepth = 0;
  Color background{0.0f};
  // <shadowrayepsilon>: when set, secondary rays start at p + e*n; otherwise the robust offset is used.
  std::optional<double> shadowRayEpsilon;

  Camera camera;
  Color ambientLight{0.0f};
  std::vector<PointLight> pointLights;
  std::vector<TriangularLight> triangularLights;
  std::vector<Material> materials;

  std::vector<glm::dvec3> vertices;
  std::vector<glm::vec2> texCoords;   // <texturedata>
  std::vector<glm::vec3> normals;     // <normaldata>
  std::vector<Mesh> meshes;
  std::vector<Triangle> triangles;    // all meshes, mesh by mesh

  std::string textureImage;           // <textureimage> as written in the file ("" when absent)
  std::optional<Texture> texture;     // loaded image, when it could be read

  std::filesystem::path sourcePath;   // the file it came from ("" for an embedded scene)

  bool hasMirrors() const;
};

}  // namespace rayview
