// rayview's own PLY reader: ASCII, binary little- and big-endian; vertices (x y z, normals nx ny nz, texture
// coordinates u v / s t), faces as index lists (polygons cut into fans), other elements skipped.

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "byte_input.h"
#include "model_parts.h"

namespace rayview::model {
namespace {

namespace fs = std::filesystem;

enum class Type { I8, U8, I16, U16, I32, U32, F32, F64, None };

struct Property {
  std::string name;
  Type type = Type::None;       // a list's item type
  Type countType = Type::None;  // a list's count type; None for a scalar
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

Type typeNamed(std::string_view name) {
  if (name == "char" || name == "int8") return Type::I8;
  if (name == "uchar" || name == "uint8") return Type::U8;
  if (name == "short" || name == "int16") return Type::I16;
  if (name == "ushort" || name == "uint16") return Type::U16;
  if (name == "int" || name == "int32") return Type::I32;
  if (name == "uint" || name == "uint32") return Type::U32;
  if (name == "float" || name == "float32") return Type::F32;
  if (name == "double" || name == "float64") return Type::F64;
  return Type::None;
}

std::size_t sizeOf(Type t) {
  switch (t) {
    case Type::I8: case Type::U8: return 1;
    case Type::I16: case Type::U16: return 2;
    case Type::I32: case Type::U32: case Type::F32: return 4;
    case Type::F64: return 8;
    default: return 0;
  }
}

struct Header {
  bool ascii = false, bigEndian = false;
  std::vector<Element> elements;
  std::size_t dataStart = 0;
};

Header parseHeader(const std::string& bytes, const fs::path& path) {
  Header h;
  // Leading blank lines before "ply" (some writers emit them; Assimp refuses such files) are tolerated.
  std::size_t at = bytes.find_first_not_of(" \t\r\n");
  if (at == std::string::npos || bytes.compare(at, 3, "ply") != 0) fail(path, "is not a PLY file (no \"ply\" header)");
  const std::size_t end = bytes.find("end_header", at);
  if (end == std::string::npos) fail(path, "PLY header has no end_header (truncated?)");
  std::size_t dataStart = bytes.find('\n', end);
  h.dataStart = dataStart == std::string::npos ? bytes.size() : dataStart + 1;
  Tokens t(std::string_view(bytes).substr(0, end), at + 3);
  bool haveFormat = false;
  for (std::string_view word = t.next(); !word.empty(); word = t.next()) {
    const int line = t.line();
    auto bad = [&](const std::string& what) { fail(path, "PLY header line " + std::to_string(line) + ": " + what); };
    if (word == "comment" || word == "obj_info") {
      // The rest of the line.
      const std::size_t eol = bytes.find('\n', t.position());
      t = Tokens(std::string_view(bytes).substr(0, end), eol == std::string::npos ? end : eol);
      continue;
    }
    if (word == "format") {
      const std::string_view format = t.next();
      t.next();  // version
      h.ascii = format == "ascii";
      h.bigEndian = format == "binary_big_endian";
      if (!h.ascii && !h.bigEndian && format != "binary_little_endian") bad("unknown format \"" + std::string(format) + "\"");
      haveFormat = true;
    } else if (word == "element") {
      Element e;
      e.name = t.next();
      double count = -1.0;
      if (!t.number(count) || count < 0.0 || count > 1e15 || count != std::floor(count)) bad("element needs a count");
      e.count = static_cast<std::uint64_t>(count);
      h.elements.push_back(std::move(e));
    } else if (word == "property") {
      if (h.elements.empty()) bad("property before any element");
      Property p;
      const std::string_view type = t.next();
      if (type == "list") {
        p.countType = typeNamed(t.next());
        p.type = typeNamed(t.next());
        if (p.countType == Type::None || p.type == Type::None || p.countType == Type::F32 || p.countType == Type::F64)
          bad("bad list property types");
      } else {
        p.type = typeNamed(type);
        if (p.type == Type::None) bad("unknown property type \"" + std::string(type) + "\"");
      }
      p.name = t.next();
      h.elements.back().properties.push_back(std::move(p));
    } else {
      bad("unexpected \"" + std::string(word.substr(0, 40)) + "\"");
    }
  }
  if (!haveFormat) fail(path, "PLY header has no format line");
  return h;
}

// Values of one element, read one after another from binary data or ASCII tokens.
class Values {
 public:
  Values(const std::string& bytes, const Header& h, const fs::path& path)
      : bytes_(bytes), h_(h), path_(path), at_(h.dataStart), tokens_(bytes, h.dataStart) {}

  double scalar(Type type) {
    if (h_.ascii) {
      double v = 0.0;
      if (!tokens_.number(v)) fail(path_, "PLY data ends early or holds a token that is not a number");
      return v;
    }
    const std::size_t size = sizeOf(type);
    if (at_ + size > bytes_.size()) fail(path_, "PLY data ends early (truncated file)");
    const char* p = bytes_.data() + at_;
    at_ += size;
    switch (type) {
      case Type::I8: return loadScalar<std::int8_t>(p, false);
      case Type::U8: return loadScalar<std::uint8_t>(p, false);
      case Type::I16: return loadScalar<std::int16_t>(p, h_.bigEndian);
      case Type::U16: return loadScalar<std::uint16_t>(p, h_.bigEndian);
      case Type::I32: return loadScalar<std::int32_t>(p, h_.bigEndian);
      case Type::U32: return loadScalar<std::uint32_t>(p, h_.bigEndian);
      case Type::F32: return loadScalar<float>(p, h_.bigEndian);
      default: return loadScalar<double>(p, h_.bigEndian);
    }
  }
  std::size_t remaining() const { return bytes_.size() - std::min(bytes_.size(), h_.ascii ? tokens_.position() : at_); }

 private:
  const std::string& bytes_;
  const Header& h_;
  const fs::path& path_;
  std::size_t at_;
  Tokens tokens_;
};

int indexOf(const Element& e, std::initializer_list<const char*> names) {
  for (std::size_t i = 0; i < e.properties.size(); ++i)
    for (const char* name : names)
      if (e.properties[i].name == name && e.properties[i].countType == Type::None) return static_cast<int>(i);
  return -1;
}

// The smallest number of bytes one item of `e` takes: a declared count beyond what the rest of the file can hold
// is refused before anything is allocated.
std::size_t minimumBytes(const Element& e, bool ascii) {
  std::size_t bytes = 0;
  for (const Property& p : e.properties) bytes += ascii ? 2 : sizeOf(p.countType == Type::None ? p.type : p.countType);
  return bytes;
}

void readVertices(Values& in, const Element& e, const fs::path& path, SceneGeometry& g) {
  const int x = indexOf(e, {"x"}), y = indexOf(e, {"y"}), z = indexOf(e, {"z"});
  if (x < 0 || y < 0 || z < 0) fail(path, "PLY vertices have no x, y and z");
  const int nx = indexOf(e, {"nx"}), ny = indexOf(e, {"ny"}), nz = indexOf(e, {"nz"});
  const int u = indexOf(e, {"u", "s", "texture_u", "texture_s"}), v = indexOf(e, {"v", "t", "texture_v", "texture_t"});
  const bool normals = nx >= 0 && ny >= 0 && nz >= 0, uvs = u >= 0 && v >= 0;
  g.vertices.reserve(e.count);
  if (normals) g.normals.reserve(e.count);
  if (uvs) g.texCoords.reserve(e.count);
  std::vector<double> item(e.properties.size());
  for (std::uint64_t i = 0; i < e.count; ++i) {
    for (std::size_t k = 0; k < e.properties.size(); ++k) {
      const Property& p = e.properties[k];
      if (p.countType == Type::None) {
        item[k] = in.scalar(p.type);
        continue;
      }
      const double n = in.scalar(p.countType);
      for (double j = 0; j < n; ++j) in.scalar(p.type);
    }
    const glm::dvec3 position(item[x], item[y], item[z]);
    if (!std::isfinite(position.x) || !std::isfinite(position.y) || !std::isfinite(position.z))
      fail(path, "vertex " + std::to_string(i + 1) + " is not a finite number");
    g.vertices.push_back(position);
    if (normals) {
      glm::vec3 n(static_cast<float>(item[nx]), static_cast<float>(item[ny]), static_cast<float>(item[nz]));
      const float length = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
      g.normals.push_back(length > 0.0f && std::isfinite(length) ? n / length : glm::vec3(0.0f, 0.0f, 1.0f));
    }
    if (uvs) g.texCoords.emplace_back(static_cast<float>(item[u]), static_cast<float>(item[v]));
  }
}

void readFaces(Values& in, const Element& e, const fs::path& path, SceneGeometry& g, Notes& notes) {
  int list = -1;
  for (std::size_t k = 0; k < e.properties.size(); ++k)
    if (e.properties[k].countType != Type::None &&
        (e.properties[k].name == "vertex_indices" || e.properties[k].name == "vertex_index"))
      list = static_cast<int>(k);
  if (list < 0) fail(path, "PLY faces have no vertex_indices list");
  const bool attributes = !g.normals.empty() || !g.texCoords.empty();
  g.triangles.reserve(e.count);
  if (attributes) g.faceAttributes.reserve(e.count);
  const double vertexCount = static_cast<double>(g.vertices.size());
  std::vector<std::uint32_t> corners;
  std::size_t dropped = 0;
  for (std::uint64_t f = 0; f < e.count; ++f) {
    for (std::size_t k = 0; k < e.properties.size(); ++k) {
      const Property& p = e.properties[k];
      if (p.countType == Type::None) {
        in.scalar(p.type);
        continue;
      }
      const double n = in.scalar(p.countType);
      if (!(n >= 0.0) || n > static_cast<double>(in.remaining()) + 1.0) fail(path, "face " + std::to_string(f + 1) + " declares " + std::to_string(static_cast<long long>(n)) + " vertices, more than the file holds");
      corners.clear();
      for (double j = 0; j < n; ++j) {
        const double index = in.scalar(p.type);
        if (static_cast<int>(k) != list) continue;
        if (!(index >= 0.0 && index < vertexCount) || index != std::floor(index))
          fail(path, "face " + std::to_string(f + 1) + " names vertex " + std::to_string(static_cast<long long>(index)) +
                         ", the file has " + std::to_string(g.vertices.size()) + " vertices");
        corners.push_back(static_cast<std::uint32_t>(index));
      }
      if (static_cast<int>(k) != list) continue;
      if (corners.size() < 3) {
        ++dropped;
        continue;
      }
      for (std::size_t j = 1; j + 1 < corners.size(); ++j) {
        const Triangle t{{corners[0], corners[j], corners[j + 1]}};
        if (!attributes) {
          g.triangles.push_back(t);
          continue;
        }
        FaceAttributes a;
        for (int c = 0; c < 3; ++c) {
          if (!g.normals.empty()) a.normal[c] = static_cast<std::int32_t>(t.vertex[c]);
          if (!g.texCoords.empty()) a.texCoord[c] = static_cast<std::int32_t>(t.vertex[c]);
        }
        g.addFace(t, a);
      }
    }
  }
  if (dropped > 0) notes.dropped.push_back(std::to_string(dropped) + " faces of fewer than 3 vertices");
}

void skip(Values& in, const Element& e) {
  for (std::uint64_t i = 0; i < e.count; ++i)
    for (const Property& p : e.properties) {
      const double n = p.countType == Type::None ? 1.0 : in.scalar(p.countType);
      for (double j = 0; j < n && in.remaining() > 0; ++j) in.scalar(p.type);
    }
}

}  // namespace

void readPly(const std::string& bytes, const fs::path& path, SceneGeometry& g, Notes& notes) {
  const Header h = parseHeader(bytes, path);
  Values in(bytes, h, path);
  bool haveVertices = false;
  for (const Element& e : h.elements) {
    const std::size_t minimum = minimumBytes(e, h.ascii);
    if (minimum > 0 && e.count > in.remaining() / minimum)
      fail(path, "PLY declares " + std::to_string(e.count) + " \"" + e.name + "\" elements, more than the rest of the file (" +
                     std::to_string(in.remaining()) + " bytes) can hold: truncated or corrupt");
    if (e.name == "vertex" && !haveVertices) {
      if (e.count > 0x7fffffffULL) fail(path, "too many vertices (over 2^31)");
      readVertices(in, e, path, g);
      haveVertices = true;
    } else if (e.name == "face" && haveVertices) {
      readFaces(in, e, path, g, notes);
    } else {
      skip(in, e);
    }
  }
  if (g.triangles.empty()) fail(path, "the file has no triangles");
  if (g.triangles.size() > 0x7fffffffULL) fail(path, "too many triangles (over 2^31)");
  g.meshes.push_back(Mesh{path.stem().string(), 0, 0, static_cast<std::uint32_t>(g.triangles.size())});
}

}  // namespace rayview::model
