// rayview's own STL reader (binary and ASCII): a triangle soup, one mesh per ASCII solid, no sharing of vertices (STL has none).

#include <cmath>
#include <cstdint>
#include <fstream>
#include <string>

#include "byte_input.h"
#include "model_parts.h"

namespace rayview::model {
namespace {

namespace fs = std::filesystem;

void addCorner(SceneGeometry& g, const fs::path& path, double x, double y, double z, std::size_t triangle) {
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
    fail(path, "triangle " + std::to_string(triangle + 1) + " has a vertex that is not a finite number");
  g.vertices.emplace_back(x, y, z);
}

void finish(SceneGeometry& g, const fs::path& path) {
  if (g.triangles.empty()) fail(path, "the file has no triangles");
  if (!g.meshes.empty()) return;  // an ASCII file's solids are its meshes
  g.meshes.push_back(Mesh{path.stem().string(), 0, 0, static_cast<std::uint32_t>(g.triangles.size())});
}

void readBinary(const std::string& bytes, std::uint32_t count, const fs::path& path, SceneGeometry& g) {
  g.vertices.reserve(static_cast<std::size_t>(count) * 3);
  g.triangles.reserve(count);
  const char* record = bytes.data() + 84;
  for (std::uint32_t t = 0; t < count; ++t, record += 50) {
    for (int k = 0; k < 3; ++k) {
      const char* p = record + 12 + 12 * k;
      addCorner(g, path, loadScalar<float>(p, false), loadScalar<float>(p + 4, false), loadScalar<float>(p + 8, false), t);
    }
    const auto first = static_cast<std::uint32_t>(3 * t);
    g.triangles.push_back(Triangle{{first, first + 1, first + 2}});
  }
}

void expect(Tokens& tokens, std::string_view word, const fs::path& path) {
  const std::string_view found = tokens.next();
  if (found != word)
    fail(path, "line " + std::to_string(tokens.line()) + ": expected \"" + std::string(word) + "\", found \"" +
                   std::string(found.substr(0, 40)) + "\"");
}

// One solid's facets, from after its "solid" word to its "endsolid"; its name names the mesh.
void readSolid(Tokens& tokens, const fs::path& path, SceneGeometry& g) {
  const std::size_t first = g.triangles.size();
  const std::size_t nameLine = static_cast<std::size_t>(tokens.line());
  std::string name;
  std::string_view word = tokens.next();
  while (!word.empty() && word != "facet" && word != "endsolid") {  // the solid's name, on the solid line
    if (static_cast<std::size_t>(tokens.line()) == nameLine) name.append(name.empty() ? "" : " ").append(word);
    word = tokens.next();
  }
  while (word == "facet") {
    expect(tokens, "normal", path);
    double ignored = 0.0;
    for (int k = 0; k < 3; ++k) tokens.number(ignored);
    expect(tokens, "outer", path);
    expect(tokens, "loop", path);
    const std::size_t triangle = g.triangles.size();
    for (int k = 0; k < 3; ++k) {
      expect(tokens, "vertex", path);
      double v[3];
      for (double& x : v)
        if (!tokens.number(x)) fail(path, "line " + std::to_string(tokens.line()) + ": a vertex needs three numbers");
      addCorner(g, path, v[0], v[1], v[2], triangle);
    }
    expect(tokens, "endloop", path);
    expect(tokens, "endfacet", path);
    if (g.vertices.size() > 0x7fffffffu) fail(path, "too many triangles");
    const auto corner = static_cast<std::uint32_t>(3 * triangle);
    g.triangles.push_back(Triangle{{corner, corner + 1, corner + 2}});
    word = tokens.next();
  }
  if (word != "endsolid") fail(path, "line " + std::to_string(tokens.line()) + ": expected \"facet\" or \"endsolid\"");
  if (g.triangles.size() == first) return;
  if (name.empty()) name = path.stem().string();
  for (const Mesh& m : g.meshes)  // ids are unique in a scene
    if (m.id == name) name.append(1, '_').append(std::to_string(g.meshes.size() + 1));
  g.meshes.push_back(Mesh{name, 0, static_cast<std::uint32_t>(first), static_cast<std::uint32_t>(g.triangles.size() - first)});
}

// Every solid of the file (CAD tools write one per part), each a mesh.
void readAscii(const std::string& text, const fs::path& path, SceneGeometry& g) {
  Tokens tokens(text);
  expect(tokens, "solid", path);
  for (;;) {
    readSolid(tokens, path, g);
    // "endsolid" may repeat the solid's name on its line; the next word after that is "solid" or the end.
    const int endLine = tokens.line();
    std::string_view word = tokens.next();
    while (!word.empty() && word != "solid" && tokens.line() == endLine) word = tokens.next();
    if (word.empty()) return;
    if (word != "solid")
      fail(path, "line " + std::to_string(tokens.line()) + ": expected \"solid\" or the end of the file after \"endsolid\"");
  }
}

}  // namespace

// True when it read `bytes` as STL into `g`; throws SceneError for a broken STL file.
bool readStl(const std::string& bytes, const fs::path& path, SceneGeometry& g) {
  if (bytes.size() >= 84) {
    const std::uint32_t count = loadScalar<std::uint32_t>(bytes.data() + 80, false);
    // A binary file's size is exact; an ASCII one ("solid ...") that happens to match is still binary.
    if (bytes.size() == 84 + 50ULL * count) {
      readBinary(bytes, count, path, g);
      finish(g, path);
      return true;
    }
    if (bytes.compare(0, 5, "solid") != 0) {
      fail(path, "a binary STL that declares " + std::to_string(count) + " triangles (" +
                     std::to_string(84 + 50ULL * count) + " bytes) but has " + std::to_string(bytes.size()) +
                     " bytes: truncated or corrupt");
    }
  }
  if (bytes.compare(0, 5, "solid") != 0) fail(path, "is neither a binary nor an ASCII STL file");
  readAscii(bytes, path, g);
  finish(g, path);
  return true;
}

std::string readWholeFile(const fs::path& path, std::string& problem) {
  std::ifstream in(path, std::ios::binary);
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  std::string bytes;
  if (!in || ec) {
    problem = "cannot be opened";
    return bytes;
  }
  bytes.resize(size);
  if (!in.read(bytes.data(), static_cast<std::streamsize>(size))) problem = "cannot be read";
  return bytes;
}

}  // namespace rayview::model
