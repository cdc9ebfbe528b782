#pragma once
// The scene as plain data, exactly what a file describes (SPEC sections 2-5), in two parts:
// - SceneParameters: what an edit changes (camera, lights, materials, background, ambient light, depth,
//   epsilon). Small, copied freely, compared with ==: edits, snapshots, undo work on it alone.
// - SceneGeometry: what the traversal structure is built from (vertices, triangles, normals, texture
//   coordinates, texture). Large, loaded once, shared, never edited.
// A Scene is both, as the loader reads them. No acceleration data, no GL.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "rayview/color.h"
#include "rayview/light_types.h"
#include "rayview/own_pages.h"
#include "rayview/pixel_bytes.h"

namespace rayview {

struct Camera {
  glm::dvec3 position{0.0};
  glm::dvec3 gaze{0.0, 0.0, -1.0};
  glm::dvec3 up{0.0, 1.0, 0.0};
  double left = -1.0, right = 1.0, bottom = -1.0, top = 1.0;  // <nearplane> l r b t
  double nearDistance = 1.0;
  int width = 0;   // <imageresolution> nx
  int height = 0;  // <imageresolution> ny

  bool operator==(const Camera&) const = default;
};

struct Material {
  std::string id;
  Color ambient{0.0f}, diffuse{0.0f}, specular{0.0f};
  float phongExponent = 1.0f;
  Color mirror{0.0f};         // <mirrorreflectance>
  float textureFactor = 0.0f;  // <texturefactor>, 2025 variant
  // <twosided>1</twosided>, rayview's extension for imported models: a face seen from behind is shaded as if seen
  // from the front (its normals flipped toward the viewer), as model viewers do; the handout's faces are one-sided.
  bool twoSided = false;
  // <textureimage> inside a <material>, rayview's extension for models with several textures: this material's
  // texture in place of the scene's ("" for the scene's, as in the handout's files).
  std::string textureImage{};
  // <emission>r g b</emission>, rayview's extension for models' emissive surfaces: light the surface gives off
  // itself, unlit and unshadowed, on the image's 0-255 scale, before the texture blend; <emissionimage> scales it by
  // a texel (each channel 0..1), for a model's emission map.
  Color emission{0.0f};
  std::string emissionImage{};
  // <metallicroughnessimage>, with <basecolor>r g b</basecolor> (0..1) and <metallicroughness>m r</metallicroughness>,
  // rayview's extension for glTF's metal: where the map applies, each hit's Phong terms come from the base colour
  // and the factors times the texel (metallic in blue, roughness in green), as docs/scene-format.md says; the other
  // fields hold those terms at the map's average, which is what readers of the handout's format see.
  std::string metalRoughImage{};
  Color baseColor{0.0f};
  float metallic = 1.0f, roughness = 1.0f;
  // <alphaimage> with <alphacutoff>c</alphacutoff> (0..1), rayview's extension for models' cut-outs (leaves, fences,
  // hair cards): where a face has texture coordinates and the image's coverage there (its alpha, else its grey level)
  // is below c, the surface is not there and every ray passes through (rayview/cut_outs.h).
  std::string alphaImage{};
  float alphaCutoff = 0.5f;

  // Every image file the material names, so that whatever finds, renames or checks one finds them all.
  std::array<const std::string*, 4> images() const {
    return {&textureImage, &emissionImage, &metalRoughImage, &alphaImage};
  }
  std::array<std::string*, 4> images() { return {&textureImage, &emissionImage, &metalRoughImage, &alphaImage}; }
  bool emits() const { return emission.x != 0.0f || emission.y != 0.0f || emission.z != 0.0f; }
  bool isMirror() const { return mirror.x != 0.0f || mirror.y != 0.0f || mirror.z != 0.0f; }
  bool operator==(const Material&) const = default;
};

// The deepest mirror recursion any scene, option or edit may ask for (<maxraytracedepth>, --depth, the
// panel, scripts). Tracing is iterative, so the limit is about time, not the stack.
inline constexpr int kMaxRayDepth = 1000000;

struct SceneParameters {
  int maxRayDepth = 0;  // 0 .. kMaxRayDepth
  Color background{0.0f};
  // <shadowrayepsilon>: when set, secondary rays start at p + e*n; otherwise the robust offset is used.
  std::optional<double> shadowRayEpsilon;

  Camera camera;
  Color ambientLight{0.0f};
  SceneLights lights;  // every light, by type (light_types.h): lights.of<PointLight>()
  std::vector<Material> materials;  // ids and order as loaded: triangles refer to them by index

  // Mirror reflections can happen: a mirror material and a depth above 0.
  bool hasMirrors() const;
  bool operator==(const SceneParameters&) const = default;
};

inline constexpr std::int32_t kNoIndex = -1;

// One face, already resolved to 0-based indices into the scene's vertices. 12 bytes: at 1e7 triangles every byte
// here is 10 MB (docs/PERFORMANCE.md, "Memory per triangle"). Its mesh and material come from the mesh ranges
// (SceneGeometry::meshOf), its corners' texture and normal indices from SceneGeometry::faceAttributes.
struct Triangle {
  std::uint32_t vertex[3] = {0, 0, 0};
};

// The texture-coordinate and normal indices of a face's corners (the 2025 format's v/t, v//n and v/t/n forms),
// kNoIndex where the face gives none.
struct FaceAttributes {
  std::int32_t texCoord[3] = {kNoIndex, kNoIndex, kNoIndex};  // into SceneGeometry::texCoords
  std::int32_t normal[3] = {kNoIndex, kNoIndex, kNoIndex};    // into SceneGeometry::normals

  bool hasTexCoords() const { return texCoord[0] != kNoIndex; }
  bool hasNormals() const { return normal[0] != kNoIndex; }
  bool any() const { return hasTexCoords() || hasNormals(); }
  bool operator==(const FaceAttributes&) const = default;
};

// Of `count` ranges starting at start(0) <= start(1) <= ..., the index of the last that starts at or before
// `triangle` (0 when none does): the mesh that holds a triangle, since an empty mesh shares its start with the next
// one. A binary search without branches (a hit's triangle is unpredictable); `start(k)` reads range k's start.
template <class Start>
std::size_t lastRangeAtOrBefore(std::size_t count, std::uint32_t triangle, Start start) {
  std::size_t first = 0;
  for (std::size_t n = count; n > 1;) {
    const std::size_t half = n / 2;
    first = start(first + half) <= triangle ? first + half : first;
    n -= half;
  }
  return first;
}

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
  PixelBytes rgb;
  // The image's alpha channel, one byte a pixel in the same order, kept apart from the colour (which is never
  // composited): empty for an image without one, and for one whose alpha is 255 everywhere (many models' RGBA
  // textures), which `opaqueAlpha` marks instead: only images with see-through pixels pay for it, and a cut-out of
  // an opaque image hides nothing rather than falling back to the grey level.
  std::vector<std::uint8_t> alpha;
  bool opaqueAlpha = false;

  bool operator==(const Texture&) const = default;
};

// An image a material names by its own <textureimage>, once per name.
struct NamedTexture {
  std::string name;               // as written in the file
  std::optional<Texture> image;   // loaded, when it could be read

  bool operator==(const NamedTexture&) const = default;
};

// A scene's big arrays: from 512 KiB on, on pages of their own advised for huge pages (rayview/own_pages.h), which a
// load first touches up to 512 times less often.
template <class T>
using SceneArray = BigArray<T>;

struct SceneGeometry {
  SceneArray<glm::dvec3> vertices;
  std::vector<glm::vec2> texCoords;   // <texturedata>
  std::vector<glm::vec3> normals;     // <normaldata>
  // <colordata> (rayview's extension, a model's vertex colours): none, or one per vertex, each channel 0..1, which
  // multiply the ambient and diffuse colours of the faces they shade.
  std::vector<Color> vertexColors;
  std::vector<Mesh> meshes;           // in order; each a range of `triangles`, together covering them all
  SceneArray<Triangle> triangles;     // all meshes, mesh by mesh
  // One per triangle when any face gives texture or normal indices, else empty: the plain faces of most scenes
  // (and of every large one so far) pay nothing for the 2025 format's attributes.
  std::vector<FaceAttributes> faceAttributes;

  std::string textureImage;           // <textureimage> as written in the file ("" when absent)
  std::optional<Texture> texture;     // loaded image, when it could be read
  std::vector<NamedTexture> materialTextures;  // the images materials name themselves, in order of first mention

  // The texture a material shows: its own (by name) or else the scene's; null when there is none to show (never
  // named, not read, or empty).
  const Texture* textureOf(const Material& material) const;
  // The image a material names itself (its texture or emission map); null when none was read under that name.
  const Texture* textureNamed(const std::string& name) const;
  // Whether any material can show a texture: the scene's or one of its own.
  bool hasAnyTexture() const;

  // The mesh a triangle belongs to (a binary search of the ranges; 0 when there are no meshes), and so its material.
  std::uint32_t meshOf(std::uint32_t triangle) const;
  std::uint32_t materialOf(std::uint32_t triangle) const {
    return meshes.empty() ? 0u : meshes[meshOf(triangle)].material;
  }
  // One past a mesh's last triangle, clamped to the triangles there are (a mesh range may claim more).
  std::size_t meshEnd(const Mesh& mesh) const {
    return std::min<std::size_t>(triangles.size(), static_cast<std::size_t>(mesh.firstTriangle) + mesh.triangleCount);
  }
  // The triangle's texture and normal indices: none (kNoIndex) when the scene has no face attributes.
  const FaceAttributes& attributesOf(std::size_t triangle) const {
    static const FaceAttributes kNone;
    return faceAttributes.empty() ? kNone : faceAttributes[triangle];
  }
  // Appends a face, keeping faceAttributes empty or one per triangle.
  void addFace(const Triangle& triangle, const FaceAttributes& attributes = {});
};

// SceneGeometry::addFace on a pair of arrays (the loader's stream keeps its faces apart from a scene).
void appendFace(SceneArray<Triangle>& triangles, std::vector<FaceAttributes>& faceAttributes, const Triangle& triangle,
                const FaceAttributes& attributes);

struct Scene : SceneParameters, SceneGeometry {
  std::filesystem::path sourcePath;   // the file it came from ("" for an embedded scene)

  SceneParameters& parameters() { return *this; }
  const SceneParameters& parameters() const { return *this; }
  const SceneGeometry& geometry() const { return *this; }
};

// What every scene the loader returns holds: the meshes are ranges of the triangles in order that cover them all,
// each with a real material, and meshOf finds each triangle's; face attributes are none or one per triangle; every
// vertex, texture-coordinate and normal index is in range. "" when it holds, else the first thing that breaks it.
// One check for the tests and the fuzz targets.
std::string wholenessProblem(const Scene& scene);

// What the loader's checks of each value guarantee of parameters that come as bytes instead of XML (the import
// worker's answer): every number finite, a camera that makes an image, depth, epsilon and exponents in range, unique
// material ids. "" when it holds, else the first thing that breaks it.
std::string parametersProblem(const SceneParameters& parameters);

}  // namespace rayview
