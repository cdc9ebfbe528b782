// The plain PLY reader (ply_reader.h): the header, then each element's records in order, ASCII or binary.

#include "ply_reader.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <optional>

#include "number_list.h"
#include "rayview/file_read.h"

namespace rayview::detail {

namespace {

enum class Kind { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

struct TypeName {
  std::string_view name;
  Kind kind;
};

constexpr TypeName kTypes[] = {
    {"char", Kind::Int8},      {"int8", Kind::Int8},       {"uchar", Kind::UInt8},     {"uint8", Kind::UInt8},
    {"short", Kind::Int16},    {"int16", Kind::Int16},     {"ushort", Kind::UInt16},   {"uint16", Kind::UInt16},
    {"int", Kind::Int32},      {"int32", Kind::Int32},     {"uint", Kind::UInt32},     {"uint32", Kind::UInt32},
    {"float", Kind::Float32},  {"float32", Kind::Float32}, {"double", Kind::Float64},  {"float64", Kind::Float64},
};

std::size_t sizeOf(Kind k) {
  switch (k) {
    case Kind::Int8: case Kind::UInt8: return 1;
    case Kind::Int16: case Kind::UInt16: return 2;
    case Kind::Int32: case Kind::UInt32: case Kind::Float32: return 4;
    case Kind::Float64: return 8;
  }
  return 1;
}

bool isInteger(Kind k) { return k != Kind::Float32 && k != Kind::Float64; }

enum class Format { Ascii, LittleEndian, BigEndian };

// What a property is for this reader: a vertex coordinate, the face's index list, or something to skip.
enum class Role { Skip, X, Y, Z, Indices };

struct Property {
  std::string name;
  Kind kind = Kind::Float32;       // the value's type (the items' type for a list)
  std::optional<Kind> countKind;   // set for a list
  Role role = Role::Skip;
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
  int line = 0;  // of its header line
};

struct Header {
  Format format = Format::Ascii;
  std::vector<Element> elements;
  std::size_t bodyStart = 0;  // the byte after end_header's line
  int bodyLine = 0;           // the line the body starts on
};

[[noreturn]] void fail(const std::string& message) { throw PlyError{message}; }

std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

Kind typeOf(std::string_view name, int line) {
  for (const TypeName& t : kTypes)
    if (t.name == name) return t.kind;
  fail("line " + std::to_string(line) + ": unknown property type '" + std::string(name.substr(0, 32)) + "'");
}

// The property line's words after "property"; the element it belongs to is the last one declared.
void addProperty(Header& header, const std::vector<std::string_view>& w, int line) {
  if (header.elements.empty()) fail("line " + std::to_string(line) + ": a property before any element");
  Property p;
  if (w.size() == 5 && w[1] == "list") {
    p.countKind = typeOf(w[2], line);
    p.kind = typeOf(w[3], line);
    if (!isInteger(*p.countKind)) fail("line " + std::to_string(line) + ": a list's count must have an integer type");
    p.name = std::string(w[4]);
  } else if (w.size() == 3) {
    p.kind = typeOf(w[1], line);
    p.name = std::string(w[2]);
  } else {
    fail("line " + std::to_string(line) + ": malformed property line");
  }
  header.elements.back().properties.push_back(std::move(p));
}

Header parseHeader(std::string_view bytes) {
  Header header;
  bool haveFormat = false;
  std::size_t pos = 0;
  for (int line = 1;; ++line) {
    if (pos >= bytes.size()) fail("the header has no end_header line (truncated, or not a PLY file)");
    std::size_t end = bytes.find('\n', pos);
    if (end == std::string_view::npos) end = bytes.size();
    std::string_view text = bytes.substr(pos, end - pos);
    if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
    pos = end + 1;
    const std::vector<std::string_view> w = words(text);
    if (line == 1) {
      if (w.size() != 1 || w[0] != "ply") fail("not a PLY file (the first line is not 'ply')");
      continue;
    }
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "end_header") {
      header.bodyStart = std::min(pos, bytes.size());
      header.bodyLine = line + 1;
      break;
    }
    if (w[0] == "format") {
      if (w.size() < 2) fail("line " + std::to_string(line) + ": malformed format line");
      if (w[1] == "ascii") header.format = Format::Ascii;
      else if (w[1] == "binary_little_endian") header.format = Format::LittleEndian;
      else if (w[1] == "binary_big_endian") header.format = Format::BigEndian;
      else fail("line " + std::to_string(line) + ": unknown format '" + std::string(w[1].substr(0, 32)) + "'");
      haveFormat = true;
    } else if (w[0] == "element") {
      std::int64_t count = -1;
      if (w.size() != 3 || parseInteger(w[2], count) != NumberStatus::Ok || count < 0)
        fail("line " + std::to_string(line) + ": malformed element line (expected: element NAME COUNT)");
      header.elements.push_back(Element{std::string(w[1]), static_cast<std::uint64_t>(count), {}, line});
    } else if (w[0] == "property") {
      addProperty(header, w, line);
    } else {
      fail("line " + std::to_string(line) + ": unknown header keyword '" + std::string(w[0].substr(0, 32)) + "'");
    }
  }
  if (!haveFormat) fail("the header has no format line");
  return header;
}

// Marks the properties this reader uses, and checks that the vertices and faces can be read.
void assignRoles(Header& header, std::uint64_t& vertexCount) {
  bool haveVertex = false, haveFace = false;
  for (Element& e : header.elements) {
    if (e.name == "vertex") {
      haveVertex = true;
      vertexCount = e.count;
      int found = 0;
      for (Property& p : e.properties) {
        if (p.countKind) continue;
        if (p.name == "x") p.role = Role::X, found |= 1;
        else if (p.name == "y") p.role = Role::Y, found |= 2;
        else if (p.name == "z") p.role = Role::Z, found |= 4;
      }
      if (found != 7) fail("line " + std::to_string(e.line) + ": the vertex element has no x, y and z properties");
    } else if (e.name == "face") {
      haveFace = true;
      auto list = std::find_if(e.properties.begin(), e.properties.end(), [](const Property& p) {
        return p.countKind && (p.name == "vertex_indices" || p.name == "vertex_index");
      });
      if (list == e.properties.end())
        fail("line " + std::to_string(e.line) + ": the face element has no vertex_indices list");
      list->role = Role::Indices;
    }
  }
  if (!haveVertex) fail("the header declares no vertex element");
  if (!haveFace) fail("the header declares no face element (a point cloud is not a mesh)");
  if (vertexCount > static_cast<std::uint64_t>(INT32_MAX)) fail("the file declares too many vertices");
}

// Refuses counts the bytes after the header cannot hold, before anything is allocated for them.
void checkCounts(const Header& header, std::uint64_t bodyBytes) {
  for (const Element& e : header.elements) {
    std::uint64_t least = 0;  // bytes of one record, at the least
    for (const Property& p : e.properties)
      least += header.format == Format::Ascii ? 2 : sizeOf(p.countKind ? *p.countKind : p.kind);
    if (least > 0 && e.count > (bodyBytes + 1) / least)
      fail("line " + std::to_string(e.line) + ": declares " + std::to_string(e.count) + " " + e.name +
           " records, more than the " + std::to_string(bodyBytes) + " bytes after the header can hold (truncated or corrupt)");
  }
}

// A record, named in messages as "face 12 of 100"; the text is made only for a message.
struct Record {
  const Element* element;
  std::uint64_t index;
  std::string describe() const {
    return element->name + " " + std::to_string(index) + " of " + std::to_string(element->count);
  }
};

// The records' values one at a time, from ASCII text or binary bytes.
class Values {
 public:
  Values(std::string_view body, Format format, int firstLine) : body_(body), format_(format), line_(firstLine) {}

  // The next value of type `kind`, of record `what`.
  double next(Kind kind, const Record& what) {
    if (format_ == Format::Ascii) return nextText(kind, what);
    const std::size_t n = sizeOf(kind);
    if (body_.size() - pos_ < n) fail("the file ends inside " + what.describe() + " (truncated)");
    unsigned char b[8];
    std::memcpy(b, body_.data() + pos_, n);
    if ((format_ == Format::BigEndian) == (std::endian::native == std::endian::little)) std::reverse(b, b + n);
    pos_ += n;
    return decode(kind, b);
  }

  // Could `count` more values of type `kind` still be in the file?
  bool couldHold(double count, Kind kind) const {
    const double least = format_ == Format::Ascii ? 2.0 : static_cast<double>(sizeOf(kind));
    return count * least <= static_cast<double>(body_.size() - pos_) + 1.0;
  }

  // Where the last value was, for a message.
  std::string where() const {
    return format_ == Format::Ascii ? "line " + std::to_string(line_) : "byte " + std::to_string(pos_);
  }

 private:
  static double decode(Kind kind, const unsigned char* b) {
    switch (kind) {
      case Kind::Int8: { std::int8_t v; std::memcpy(&v, b, 1); return v; }
      case Kind::UInt8: return b[0];
      case Kind::Int16: { std::int16_t v; std::memcpy(&v, b, 2); return v; }
      case Kind::UInt16: { std::uint16_t v; std::memcpy(&v, b, 2); return v; }
      case Kind::Int32: { std::int32_t v; std::memcpy(&v, b, 4); return v; }
      case Kind::UInt32: { std::uint32_t v; std::memcpy(&v, b, 4); return v; }
      case Kind::Float32: { float v; std::memcpy(&v, b, 4); return v; }
      case Kind::Float64: { double v; std::memcpy(&v, b, 8); return v; }
    }
    return 0.0;
  }

  double nextText(Kind kind, const Record& what) {
    while (pos_ < body_.size() && isXmlSpace(body_[pos_])) line_ += body_[pos_++] == '\n';
    if (pos_ == body_.size()) fail("the file ends inside " + what.describe() + " (truncated)");
    const std::size_t start = pos_;
    while (pos_ < body_.size() && !isXmlSpace(body_[pos_])) ++pos_;
    const std::string_view token = body_.substr(start, pos_ - start);
    double v = 0.0;
    if (parseDouble(token, v) != NumberStatus::Ok)
      fail("line " + std::to_string(line_) + ": expected a number in " + what.describe() + ", found '" +
           std::string(token.substr(0, 32)) + "'");
    if (isInteger(kind) && v != std::floor(v))
      fail("line " + std::to_string(line_) + ": expected an integer in " + what.describe() + ", found '" +
           std::string(token.substr(0, 32)) + "'");
    return v;
  }

  std::string_view body_;
  Format format_;
  std::size_t pos_ = 0;
  int line_;
};

// One face's index list: checked against the vertices and split into a fan.
void addPolygon(PlyMesh& mesh, const std::vector<double>& indices, std::uint64_t vertexCount, std::uint64_t face,
                const Values& values) {
  for (const double i : indices)
    if (!(i >= 0.0) || i >= static_cast<double>(vertexCount) || i != std::floor(i))
      fail(values.where() + ": face " + std::to_string(face) + " uses vertex " + std::to_string(static_cast<long long>(i)) +
           ", but the file has " + std::to_string(vertexCount) + " vertices (indices 0.." +
           std::to_string(static_cast<long long>(vertexCount) - 1) + ")");
  if (indices.size() < 3) {
    ++mesh.skippedFaces;
    return;
  }
  if (mesh.triangles.size() + indices.size() > static_cast<std::size_t>(UINT32_MAX / 2)) fail("too many triangles");
  for (std::size_t k = 1; k + 1 < indices.size(); ++k)
    mesh.triangles.push_back({static_cast<std::uint32_t>(indices[0]), static_cast<std::uint32_t>(indices[k]),
                              static_cast<std::uint32_t>(indices[k + 1])});
}

void readRecords(const Header& header, std::string_view body, std::uint64_t vertexCount, PlyMesh& mesh) {
  Values values(body, header.format, header.bodyLine);
  std::vector<double> indices;
  for (const Element& e : header.elements) {
    if (e.properties.empty()) continue;  // nothing to read, whatever the count
    const bool vertex = e.name == "vertex", face = e.name == "face";
    if (vertex) mesh.vertices.reserve(e.count);
    // No more than the file could hold, whatever the count says.
    if (face) mesh.triangles.reserve(std::min<std::uint64_t>(e.count, body.size() / 4));
    for (std::uint64_t r = 0; r < e.count; ++r) {
      const Record what{&e, r};
      glm::dvec3 position(0.0);
      for (const Property& p : e.properties) {
        if (p.countKind) {
          const double count = values.next(*p.countKind, what);
          if (count < 0.0) fail(values.where() + ": " + what.describe() + " has a negative list length");
          if (!values.couldHold(count, p.kind))
            fail(values.where() + ": " + what.describe() + " declares a list of " + std::to_string(static_cast<long long>(count)) +
                 " values, more than the rest of the file holds (truncated or corrupt)");
          if (p.role == Role::Indices) indices.clear();
          for (double k = 0; k < count; ++k) {
            const double v = values.next(p.kind, what);
            if (p.role == Role::Indices) indices.push_back(v);
          }
          continue;
        }
        const double v = values.next(p.kind, what);
        if (p.role == Role::X) position.x = v;
        else if (p.role == Role::Y) position.y = v;
        else if (p.role == Role::Z) position.z = v;
      }
      if (vertex) {
        if (!std::isfinite(position.x) || !std::isfinite(position.y) || !std::isfinite(position.z))
          fail(values.where() + ": vertex " + std::to_string(r) + " has a coordinate that is not a finite number");
        mesh.vertices.push_back(position);
      } else if (face) {
        addPolygon(mesh, indices, vertexCount, r, values);
      }
    }
  }
}

}  // namespace

PlyMesh parsePly(std::string_view bytes) {
  Header header = parseHeader(bytes);
  std::uint64_t vertexCount = 0;
  assignRoles(header, vertexCount);
  const std::string_view body = bytes.substr(header.bodyStart);
  checkCounts(header, body.size());
  PlyMesh mesh;
  readRecords(header, body, vertexCount, mesh);
  return mesh;
}

PlyMesh readPlyFile(const std::filesystem::path& path) {
  UserFileRead file = readUserFile(path, kMaxPlyBytes, [](std::string_view start) {
    return start.substr(0, 3) == "ply" ? std::string() : std::string("is not a PLY file (it does not start with 'ply')");
  });
  if (file.notFound) fail("not found");
  if (!file.problem.empty()) fail(file.problem);
  return parsePly(file.bytes);
}

}  // namespace rayview::detail
