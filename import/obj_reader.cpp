// rayview's OBJ reader (obj_reader.h): one pass over the lines; v, vt and vn go straight into the scene's shared
// arrays and faces name them by index, so nothing is copied per corner.

#include "obj_reader.h"

#include <assimp/scene.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

#include "byte_input.h"
#include "rayview/diagnostics.h"
#include "rayview/input_files.h"

namespace rayview::model {
namespace {

namespace fs = std::filesystem;

constexpr long long kMaxItems = std::numeric_limits<std::int32_t>::max();

bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && isBlank(s.front())) s.remove_prefix(1);
  while (!s.empty() && isBlank(s.back())) s.remove_suffix(1);
  return s;
}

std::string_view word(std::string_view& s) {
  s = trimmed(s);
  std::size_t n = 0;
  while (n < s.size() && !isBlank(s[n])) ++n;
  const std::string_view w = s.substr(0, n);
  s.remove_prefix(n);
  return w;
}

// The largest positive index of one kind the faces used, and the first line that used it: positive indices may
// name elements defined later in the file (Assimp resolves them at the end too), so they are checked at the end.
struct HighestIndex {
  long long index = 0;
  int line = 0;
};

class ObjParser {
 public:
  ObjParser(const fs::path& path, SceneGeometry& g, Notes& notes) : path_(path), g_(g), notes_(notes) {}

  void parse(std::string_view text) {
    while (!text.empty()) {
      ++line_;
      const char* newline = static_cast<const char*>(std::memchr(text.data(), '\n', text.size()));
      const std::size_t end = newline ? static_cast<std::size_t>(newline - text.data()) : text.size();
      statement(text.substr(0, end));
      text.remove_prefix(std::min(end + 1, text.size()));
    }
  }

  ObjMaterials finish();

 private:
  [[noreturn]] void failAt(const std::string& message) const {
    throwSceneError(SourceLocation{path_.string(), line_}, message);
  }

  void statement(std::string_view line) {
    const std::string_view key = word(line);
    if (key.empty() || key[0] == '#') return;
    if (key == "v") vertex(line);
    else if (key == "vn") normal(line);
    else if (key == "vt") texCoord(line);
    else if (key == "f" || key == "fo") face(line);
    else if (key == "o" || key == "g") name(line);
    else if (key == "usemtl") useMaterial(std::string(trimmed(cutComment(line))));
    else if (key == "mtllib") library(std::string(trimmed(cutComment(line))));
    else if (key == "p" || key == "l") ++pointsAndLines_;
    // Smoothing groups, curves, and whatever else a writer adds say nothing rayview can draw.
  }

  static std::string_view cutComment(std::string_view s) {
    const std::size_t hash = s.find('#');
    return hash == std::string_view::npos ? s : s.substr(0, hash);
  }

  // The next number on the line; `required` ones must be there.
  bool number(std::string_view& rest, double& value, bool required, const char* what, bool finite = true) {
    std::string_view w = word(rest);
    if (w.empty() || w[0] == '#') {
      if (required) failAt(std::string("expected ") + what + ", found the end of the line");
      return false;
    }
    if (w[0] == '+') w.remove_prefix(1);
    const auto [end, error] = std::from_chars(w.data(), w.data() + w.size(), value);
    if (error != std::errc() || end != w.data() + w.size() || w.empty())
      failAt(std::string("expected ") + what + ", found '" + std::string(w.substr(0, 32)) + "'");
    if (finite && !std::isfinite(value)) failAt(std::string(what) + " is not a finite number");
    return true;
  }

  void vertex(std::string_view rest) {
    glm::dvec3 p;
    for (int c = 0; c < 3; ++c) number(rest, p[c], true, "a vertex coordinate");
    if (static_cast<long long>(g_.vertices.size()) >= kMaxItems) failAt("too many vertices (over 2^31)");
    g_.vertices.push_back(p);
    double extra[4] = {};
    int count = 0;
    while (count < 4 && number(rest, extra[count], false, "a vertex value")) ++count;
    // x y z r g b (MeshLab's and others' vertex colours; a fourth value is alpha): one per vertex, white for the
    // vertices of the file that have none.
    if (count >= 3) {
      colors_.resize(g_.vertices.size() - 1, Color(1.0f));
      colors_.emplace_back(static_cast<float>(extra[0]), static_cast<float>(extra[1]), static_cast<float>(extra[2]));
    } else if (!colors_.empty()) {
      colors_.emplace_back(1.0f);
    }
  }

  void normal(std::string_view rest) {
    glm::dvec3 n;
    for (int c = 0; c < 3; ++c) number(rest, n[c], true, "a normal coordinate", false);  // a bad one is dropped
    const double length = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    const bool usable = length > 0.0 && std::isfinite(length);
    badNormal_.push_back(!usable);
    g_.normals.push_back(usable ? glm::vec3(n / length) : glm::vec3(0.0f, 0.0f, 1.0f));
  }

  void texCoord(std::string_view rest) {
    double u = 0.0, v = 0.0, w = 0.0;
    number(rest, u, true, "a texture coordinate");
    number(rest, v, false, "a texture coordinate");
    number(rest, w, false, "a texture coordinate");
    g_.texCoords.emplace_back(static_cast<float>(u), static_cast<float>(v));
  }

  std::int32_t resolve(std::string_view text, std::size_t count, HighestIndex& highest, const char* kind);
  void face(std::string_view rest);
  void startMeshIfChanged();
  void name(std::string_view rest) {
    std::string joined;
    for (std::string_view w = word(rest); !w.empty() && w[0] != '#'; w = word(rest))
      joined.append(joined.empty() ? "" : " ").append(w);
    if (joined != name_) changed_ = true;
    name_ = std::move(joined);
  }
  void useMaterial(const std::string& material);
  void library(const std::string& names);
  bool readLibrary(const fs::path& file);

  const fs::path& path_;
  SceneGeometry& g_;
  Notes& notes_;
  ObjMaterials materials_;
  int line_ = 0;
  std::string name_;
  unsigned material_ = 0;
  bool haveMaterial_ = false, changed_ = true;
  std::vector<Color> colors_;  // empty when no vertex has a colour
  std::size_t pointsAndLines_ = 0;
  std::vector<bool> badNormal_;
  HighestIndex highest_[3];  // v, vt, vn
  std::vector<std::int32_t> corners_[3];
  std::unordered_map<std::string, int> meshIds_;
  std::vector<std::string> libraries_;
};

// One index of a face corner: positive from the file's start, negative back from the last one defined so far.
std::int32_t ObjParser::resolve(std::string_view text, std::size_t count, HighestIndex& highest, const char* kind) {
  long long i = 0;
  const char* first = text.data() + (!text.empty() && text[0] == '+');
  const auto [end, error] = std::from_chars(first, text.data() + text.size(), i);
  if (text.empty() || error != std::errc() || end != text.data() + text.size())
    failAt(std::string("expected a ") + kind + " index, found '" + std::string(text.substr(0, 32)) + "'");
  if (i > 0) {
    if (i > kMaxItems) failAt(std::string("a face names ") + kind + " " + std::to_string(i) + ", more than can exist");
    if (i > highest.index) highest = HighestIndex{i, line_};
    return static_cast<std::int32_t>(i - 1);
  }
  const long long resolved = static_cast<long long>(count) + i;
  if (i == 0 || resolved < 0)
    failAt(std::string("a face names ") + kind + " " + std::to_string(i) + ", but " + std::to_string(count) + " " + kind +
           (count == 1 ? " is" : "s are") + " defined before it (indices start at 1; -1 is the last)");
  return static_cast<std::int32_t>(resolved);
}

void ObjParser::face(std::string_view rest) {
  static const char* const kKinds[3] = {"vertex", "texture coordinate", "normal"};
  const std::size_t counts[3] = {g_.vertices.size(), g_.texCoords.size(), g_.normals.size()};
  for (auto& c : corners_) c.clear();
  bool partial[3] = {false, false, false};
  for (std::string_view token = word(rest); !token.empty() && token[0] != '#'; token = word(rest)) {
    for (int k = 0; k < 3; ++k) {  // v, v/t, v//n, v/t/n
      const std::size_t slash = token.find('/');
      const std::string_view part = token.substr(0, slash);
      if (!part.empty()) corners_[k].push_back(resolve(part, counts[k], highest_[k], kKinds[k]));
      else if (k == 0) failAt("a face corner has no vertex index");
      else partial[k] = true;
      if (slash == std::string_view::npos) {
        for (int rest2 = k + 1; rest2 < 3; ++rest2) partial[rest2] = true;
        break;
      }
      token.remove_prefix(slash + 1);
    }
  }
  const std::size_t n = corners_[0].size();
  if (n < 3) {
    ++pointsAndLines_;
    return;
  }
  startMeshIfChanged();
  // A corner without a texture coordinate or normal leaves the whole face without them.
  const bool uv = !partial[1] && corners_[1].size() == n, normals = !partial[2] && corners_[2].size() == n;
  for (std::size_t k = 1; k + 1 < n; ++k) {  // a fan, as Assimp cuts convex polygons
    if (static_cast<long long>(g_.triangles.size()) >= kMaxItems) failAt("too many triangles (over 2^31)");
    const std::size_t corner[3] = {0, k, k + 1};
    Triangle t;
    FaceAttributes a;
    for (int c = 0; c < 3; ++c) {
      t.vertex[c] = static_cast<std::uint32_t>(corners_[0][corner[c]]);
      if (uv) a.texCoord[c] = corners_[1][corner[c]];
      if (normals) a.normal[c] = corners_[2][corner[c]];
    }
    g_.addFace(t, a);
  }
}

// A new mesh when the group, object or material changed since the last face (a name or material without faces
// makes none).
void ObjParser::startMeshIfChanged() {
  if (!haveMaterial_) {
    material_ = materials_.defaultMaterial();
    haveMaterial_ = true;
  }
  if (!changed_ && !g_.meshes.empty()) return;
  changed_ = false;
  const auto first = static_cast<std::uint32_t>(g_.triangles.size());
  if (!g_.meshes.empty()) g_.meshes.back().triangleCount = first - g_.meshes.back().firstTriangle;
  std::string id = name_.empty() ? path_.stem().string() : name_;
  if (const int seen = meshIds_[id]++; seen > 0) id.append(1, '_').append(std::to_string(seen + 1));
  g_.meshes.push_back(Mesh{std::move(id), material_, first, 0});
}

void ObjParser::useMaterial(const std::string& material) {
  const auto it = materials_.byName.find(material);
  unsigned index = 0;
  if (it != materials_.byName.end()) {
    index = it->second;
  } else {
    // As Assimp does: a material no library defines is made, grey, under its name.
    notes_.warnings.push_back("line " + std::to_string(line_) + ": material \"" + material +
                              "\" is not defined in the model's MTL files; it is grey");
    index = materials_.named(material);
  }
  if (!haveMaterial_ || index != material_) changed_ = true;
  material_ = index;
  haveMaterial_ = true;
}

// An mtllib line names one file (whose name may hold spaces) or several separated by spaces.
void ObjParser::library(const std::string& names) {
  std::error_code ec;
  if (names.empty()) return;
  if (fs::is_regular_file(materialLibraryPath(path_, names), ec)) {
    readLibrary(materialLibraryPath(path_, names));
    return;
  }
  std::string_view rest = names;
  for (std::string_view w = word(rest); !w.empty(); w = word(rest)) {
    const fs::path file = materialLibraryPath(path_, std::string(w));
    if (!readLibrary(file))
      notes_.warnings.push_back("material library \"" + std::string(w) + "\" (line " + std::to_string(line_) +
                                ") cannot be read; its materials are grey");
  }
}

// Reads one MTL file once; false when it cannot be read.
bool ObjParser::readLibrary(const fs::path& file) {
  for (const std::string& seen : libraries_)
    if (seen == file.string()) return true;
  std::error_code ec;
  const fs::file_status status = fs::status(file, ec);
  if (ec || !fs::exists(status)) return false;
  // A FIFO, socket or device would block or never end: refused at once, by name, as the other readers' files.
  if (!fs::is_regular_file(status))
    fail(path_, "names \"" + file.string() + "\", which is not a regular file (a FIFO, socket or device is never read)");
  std::string problem;
  const std::string text = readWholeFile(file, problem);
  if (!problem.empty()) return false;
  rememberInput(file, "the model's material library");
  libraries_.push_back(file.string());
  parseMaterialLibrary(text, materials_, file);
  return true;
}

ObjMaterials ObjParser::finish() {
  static const char* const kKinds[3] = {"vertex", "texture coordinate", "normal"};
  const std::size_t counts[3] = {g_.vertices.size(), g_.texCoords.size(), g_.normals.size()};
  for (int k = 0; k < 3; ++k)
    if (highest_[k].index > static_cast<long long>(counts[k]))
      throwSceneError(SourceLocation{path_.string(), highest_[k].line},
                      std::string("a face names ") + kKinds[k] + " " + std::to_string(highest_[k].index) +
                          ", but the file has " + std::to_string(counts[k]) + " (indices 1.." +
                          std::to_string(counts[k]) + ")");
  if (g_.triangles.empty()) fail(path_, "the file has no triangles (no faces of 3 or more vertices)");
  g_.meshes.back().triangleCount = static_cast<std::uint32_t>(g_.triangles.size()) - g_.meshes.back().firstTriangle;
  // A normal of no length leaves out the normals of the faces that use it, and only theirs.
  std::size_t facesWithoutNormals = 0;
  for (FaceAttributes& a : g_.faceAttributes) {
    if (!a.hasNormals()) continue;
    bool bad = false;
    for (std::int32_t n : a.normal) bad |= badNormal_[static_cast<std::size_t>(n)];
    if (!bad) continue;
    for (std::int32_t& n : a.normal) n = kNoIndex;
    ++facesWithoutNormals;
  }
  if (pointsAndLines_ > 0) notes_.dropped.push_back(std::to_string(pointsAndLines_) + " points and lines");
  if (facesWithoutNormals > 0)
    notes_.dropped.push_back("the normals of " + std::to_string(facesWithoutNormals) +
                             " triangles (a normal of zero length or not finite)");
  if (!colors_.empty()) {
    // Colours written as 0..255 rather than 0..1 are taken as bytes.
    float most = 0.0f;
    for (const Color& c : colors_) most = std::max({most, c.x, c.y, c.z});
    for (Color& c : colors_) c = glm::clamp(most > 1.0f ? c / 255.0f : c, Color(0.0f), Color(1.0f));
    colors_.resize(g_.vertices.size(), Color(1.0f));
    g_.vertexColors = std::move(colors_);
  }
  return std::move(materials_);
}

}  // namespace

ObjMaterials readObj(const fs::path& path, SceneGeometry& g, Notes& notes) {
  std::string problem;
  const std::string text = readWholeFile(path, problem);
  if (!problem.empty()) fail(path, problem);
  ObjParser parser(path, g, notes);
  parser.parse(text);
  return parser.finish();
}

}  // namespace rayview::model
