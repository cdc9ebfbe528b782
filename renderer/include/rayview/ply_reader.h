#pragma once
// rayview's PLY reader (ASCII, binary little- and big-endian): the vertices' x, y, z, their normals (nx ny nz)
// texture coordinates (u v, s t) and colours (red green blue) when the file has them, and the faces' vertex index
// lists, polygons split into triangle fans (or, in a file with tristrips instead of faces, the strips' triangles).
// Header lines it does not know are passed over; an ASCII record's extra values at the end of its line too. Every other element and property is skipped. Used for the CENG477 dialect's
// <Faces plyFile="..."> and by the model importer (import/); refuses a truncated or implausible file instead of
// guessing.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "rayview/scene.h"

namespace rayview::detail {

struct PlyMesh {
  SceneArray<glm::dvec3> vertices;
  std::vector<glm::vec3> normals;      // one per vertex as the file gives it (not normalized), or none
  std::vector<glm::vec2> texCoords;    // one per vertex, or none
  std::vector<glm::vec3> colors;       // one per vertex (red, green, blue in 0..1 for integer colours), or none
  SceneArray<Triangle> triangles;     // 0-based indices into `vertices`
  std::size_t skippedFaces = 0;        // faces of fewer than three vertices
};

// What is wrong with a PLY file; the message does not name the file (the caller does), but says where in it
// ("line 12", "byte 4096" after the header) when it can.
struct PlyError {
  std::string message;
};

// The largest PLY file readPlyFile reads (it is held whole while it is parsed).
inline constexpr std::uintmax_t kMaxPlyBytes = (std::uintmax_t{1} << 31) - 1;

// Parses a whole PLY file's bytes. Throws PlyError.
PlyMesh parsePly(std::string_view bytes);

// Reads and parses the file at `path` (a regular file only, never a blocking open). Throws PlyError.
PlyMesh readPlyFile(const std::filesystem::path& path);

}  // namespace rayview::detail
