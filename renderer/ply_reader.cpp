// The PLY reader (ply_reader.h): the header, then each element's records in order, ASCII or binary, each value
// read straight into the slot its property fills.

#include "rayview/ply_reader.h"

#include <algorithm>
#include <bit>
#include <charconv>
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

constexpr std::size_t sizeOf(Kind k) {
  switch (k) {
    case Kind::Int8: case Kind::UInt8: return 1;
    case Kind::Int16: case Kind::UInt16: return 2;
    case Kind::Int32: case Kind::UInt32: case Kind::Float32: return 4;
    case Kind::Float64: return 8;
  }
  return 1;
}

constexpr bool isInteger(Kind k) { return k != Kind::Float32 && k != Kind::Float64; }

enum class Format { Ascii, LittleEndian, BigEndian };

struct Property {
  std::string name;
  Kind kind = Kind::Float32;       // the value's type (the items' type for a list)
  std::optional<Kind> countKind;   // set for a list
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

// The vertex values this reader keeps, in the order of Layout::slot.
enum Slot { X, Y, Z, NX, NY, NZ, U, V, R, G, B, kSlots };

// Which properties fill what: the first vertex and face elements, the vertex slots' property indices (-1: none).
struct Layout {
  const Element* vertex = nullptr;
  const Element* face = nullptr;  // the face element, or else the tristrips one
  bool strips = false;            // `face` is a tristrips element: -1 ends a strip
  int slot[kSlots] = {-1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1};
  std::size_t indexList = 0;  // the face's vertex_indices property
  bool normals = false, texCoords = false, colors = false;
  double colorScale = 1.0;  // 1/255 for integer colours
};

[[noreturn]] void fail(const std::string& message) { throw PlyError{message}; }

std::string at(int line) { return "line " + std::to_string(line) + ": "; }

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
  fail(at(line) + "unknown property type '" + std::string(name.substr(0, 32)) + "'");
}

// The property line's words after "property"; the element it belongs to is the last one declared.
void addProperty(Header& header, const std::vector<std::string_view>& w, int line) {
  if (header.elements.empty()) fail(at(line) + "a property before any element");
  Property p;
  if (w.size() == 5 && w[1] == "list") {
    p.countKind = typeOf(w[2], line);
    p.kind = typeOf(w[3], line);
    if (!isInteger(*p.countKind)) fail(at(line) + "a list's count must have an integer type");
    p.name = std::string(w[4]);
  } else if (w.size() == 3) {
    p.kind = typeOf(w[1], line);
    p.name = std::string(w[2]);
  } else {
    fail(at(line) + "malformed property line");
  }
  header.elements.back().properties.push_back(std::move(p));
}

// One header line after "ply" (not a comment); true at end_header.
bool readHeaderLine(Header& header, const std::vector<std::string_view>& w, int line, bool& haveFormat) {
  if (w[0] == "end_header") return true;
  if (w[0] == "format") {
    if (w.size() < 2) fail(at(line) + "malformed format line");
    if (w[1] == "ascii") header.format = Format::Ascii;
    else if (w[1] == "binary_little_endian") header.format = Format::LittleEndian;
    else if (w[1] == "binary_big_endian") header.format = Format::BigEndian;
    else fail(at(line) + "unknown format '" + std::string(w[1].substr(0, 32)) + "'");
    haveFormat = true;
  } else if (w[0] == "element") {
    std::int64_t count = -1;
    if (w.size() != 3 || parseInteger(w[2], count) != NumberStatus::Ok || count < 0)
      fail(at(line) + "malformed element line (expected: element NAME COUNT)");
    header.elements.push_back(Element{std::string(w[1]), static_cast<std::uint64_t>(count), {}, line});
  } else if (w[0] == "property") {
    addProperty(header, w, line);
  }
  // Any other line ("Created by ...", obj_info variants, a writer's own keywords) is passed over, as Assimp's and
  // VTK's readers do: it says nothing about the records.
  return false;
}

Header parseHeader(std::string_view bytes) {
  Header header;
  bool haveFormat = false, sawPly = false;
  std::size_t pos = 0;
  for (int line = 1;; ++line) {
    if (pos >= bytes.size())
      fail(sawPly ? "the header has no end_header line (truncated, or not a PLY file)"
                  : "not a PLY file (the first line is not 'ply')");
    std::size_t end = bytes.find('\n', pos);
    if (end == std::string_view::npos) end = bytes.size();
    std::string_view text = bytes.substr(pos, end - pos);
    if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
    pos = end + 1;
    const std::vector<std::string_view> w = words(text);
    if (!sawPly) {
      if (w.empty()) continue;  // blank lines before "ply", which some writers emit
      if (w.size() != 1 || w[0] != "ply") fail("not a PLY file (the first line is not 'ply')");
      sawPly = true;
      continue;
    }
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    if (readHeaderLine(header, w, line, haveFormat)) {
      header.bodyStart = std::min(pos, bytes.size());
      header.bodyLine = line + 1;
      break;
    }
  }
  if (!haveFormat) fail("the header has no format line");
  return header;
}

// The first scalar property of `e` with one of `names`, or -1.
int propertyNamed(const Element& e, std::initializer_list<std::string_view> names) {
  for (std::size_t k = 0; k < e.properties.size(); ++k)
    if (!e.properties[k].countKind && std::find(names.begin(), names.end(), e.properties[k].name) != names.end())
      return static_cast<int>(k);
  return -1;
}

// Finds the vertex and face elements and the properties this reader uses.
Layout layoutOf(const Header& header) {
  Layout layout;
  const Element* strips = nullptr;
  for (const Element& e : header.elements) {
    if (e.name == "vertex" && !layout.vertex) layout.vertex = &e;
    if (e.name == "face" && !layout.face) layout.face = &e;
    if (e.name == "tristrips" && !strips) strips = &e;
  }
  if (!layout.vertex) fail("the header declares no vertex element");
  if (!layout.face && strips) {
    layout.face = strips;
    layout.strips = true;
  }
  if (!layout.face) fail("the header declares no face element, nor tristrips (a point cloud is not a mesh)");
  const Element& v = *layout.vertex;
  const std::initializer_list<std::string_view> names[kSlots] = {
      {"x"}, {"y"}, {"z"}, {"nx"}, {"ny"}, {"nz"}, {"u", "s", "texture_u", "texture_s"}, {"v", "t", "texture_v", "texture_t"},
      {"red", "diffuse_red", "r"}, {"green", "diffuse_green", "g"}, {"blue", "diffuse_blue", "b"}};
  for (int s = 0; s < kSlots; ++s) layout.slot[s] = propertyNamed(v, names[s]);
  if (layout.slot[X] < 0 || layout.slot[Y] < 0 || layout.slot[Z] < 0)
    fail(at(v.line) + "the vertex element has no x, y and z properties");
  layout.normals = layout.slot[NX] >= 0 && layout.slot[NY] >= 0 && layout.slot[NZ] >= 0;
  layout.texCoords = layout.slot[U] >= 0 && layout.slot[V] >= 0;
  layout.colors = layout.slot[R] >= 0 && layout.slot[G] >= 0 && layout.slot[B] >= 0;
  if (layout.colors && isInteger(v.properties[static_cast<std::size_t>(layout.slot[R])].kind)) layout.colorScale = 1.0 / 255.0;
  const auto& faceProperties = layout.face->properties;
  const auto list = std::find_if(faceProperties.begin(), faceProperties.end(), [](const Property& p) {
    return p.countKind && (p.name == "vertex_indices" || p.name == "vertex_index");
  });
  if (list == faceProperties.end()) fail(at(layout.face->line) + "the face element has no vertex_indices list");
  layout.indexList = static_cast<std::size_t>(list - faceProperties.begin());
  return layout;
}

// Refuses counts the bytes after the header cannot hold, before anything is allocated for them.
void checkCounts(const Header& header, std::uint64_t bodyBytes) {
  for (const Element& e : header.elements) {
    std::uint64_t least = 0;  // bytes of one record, at the least
    for (const Property& p : e.properties)
      least += header.format == Format::Ascii ? 2 : sizeOf(p.countKind ? *p.countKind : p.kind);
    if (least > 0 && e.count > (bodyBytes + 1) / least)
      fail(at(e.line) + "declares " + std::to_string(e.count) + " " + e.name + " records, more than the rest of the file (" +
           std::to_string(bodyBytes) + " bytes after the header) can hold (truncated or corrupt)");
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

template <class T>
double load(const char* p, bool swap) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, p, sizeof(T));
  if (swap) std::reverse(b, b + sizeof(T));
  T v;
  std::memcpy(&v, b, sizeof(T));
  return static_cast<double>(v);
}

// The records' values one at a time, from ASCII text or binary bytes.
class Values {
 public:
  Values(std::string_view body, Format format, int firstLine)
      : body_(body), format_(format), swap_((format == Format::BigEndian) == (std::endian::native == std::endian::little)),
        line_(firstLine) {}

  // The next value of type `kind`, of record `what`; inlined into the record loops, the binary case being most
  // of a large file's time.
  [[gnu::always_inline]] double next(Kind kind, const Record& what) {
    if (format_ == Format::Ascii) return nextText(kind, what);
    const std::size_t n = sizeOf(kind);
    if (body_.size() - pos_ < n) endsInside(what);
    const char* p = body_.data() + pos_;
    pos_ += n;
    switch (kind) {
      case Kind::Int8: return load<std::int8_t>(p, false);
      case Kind::UInt8: return load<std::uint8_t>(p, false);
      case Kind::Int16: return load<std::int16_t>(p, swap_);
      case Kind::UInt16: return load<std::uint16_t>(p, swap_);
      case Kind::Int32: return load<std::int32_t>(p, swap_);
      case Kind::UInt32: return load<std::uint32_t>(p, swap_);
      case Kind::Float32: return load<float>(p, swap_);
      case Kind::Float64: return load<double>(p, swap_);
    }
    return 0.0;
  }

  // A list's length, refused when negative or when the rest of the file could not hold its values.
  double listLength(const Property& p, const Record& what) {
    const double count = next(*p.countKind, what);
    const double least = format_ == Format::Ascii ? 2.0 : static_cast<double>(sizeOf(p.kind));
    if (count < 0.0 || count * least > static_cast<double>(body_.size() - pos_) + 1.0) badLength(count, what);
    return count;
  }

  [[noreturn, gnu::noinline, gnu::cold]] void badLength(double count, const Record& what) const {
    if (count < 0.0) fail(where() + ": " + what.describe() + " has a negative list length");
    fail(where() + ": " + what.describe() + " declares a list of " + std::to_string(static_cast<long long>(count)) +
         " values, more than the rest of the file holds (truncated or corrupt)");
  }

  // After an ASCII record: values left on its line are passed over (each record has its own line, as Assimp reads
  // them), so a writer's extra columns do not shift every record after them.
  void endRecord() {
    if (format_ != Format::Ascii) return;
    while (pos_ < body_.size() && (body_[pos_] == ' ' || body_[pos_] == '\t' || body_[pos_] == '\r')) ++pos_;
    if (pos_ == body_.size() || body_[pos_] == '\n') return;
    const std::size_t end = body_.find('\n', pos_);
    pos_ = end == std::string_view::npos ? body_.size() : end;
  }

  // Where the last value was, for a message.
  std::string where() const {
    return format_ == Format::Ascii ? "line " + std::to_string(line_) : "byte " + std::to_string(pos_);
  }

 private:
  // Out of line, so that next() stays small enough to be inlined into the record loops.
  [[noreturn, gnu::noinline, gnu::cold]] static void endsInside(const Record& what) {
    fail("the file ends inside " + what.describe() + " (truncated)");
  }

  [[gnu::noinline]] double nextText(Kind kind, const Record& what) {
    while (pos_ < body_.size() && isXmlSpace(body_[pos_])) line_ += body_[pos_++] == '\n';
    if (pos_ == body_.size()) endsInside(what);
    // Most tokens are plain numbers from_chars reads in one pass; the rest take parseDouble's slower, exact way.
    const char* start = body_.data() + pos_;
    const char* end = body_.data() + body_.size();
    double v = 0.0;
    const auto [stop, error] = std::from_chars(start, end, v, std::chars_format::general);
    if (stop == start || error != std::errc() || (stop != end && !isXmlSpace(*stop)) || !std::isfinite(v))
      return slowText(kind, what);
    pos_ += static_cast<std::size_t>(stop - start);
    if (isInteger(kind) && v != std::floor(v)) notA("an integer", std::string_view(start, stop - start), what);
    return v;
  }

  double slowText(Kind kind, const Record& what) {
    const std::size_t start = pos_;
    while (pos_ < body_.size() && !isXmlSpace(body_[pos_])) ++pos_;
    const std::string_view token = body_.substr(start, pos_ - start);
    double v = 0.0;
    if (parseDouble(token, v) != NumberStatus::Ok) notA("a number", token, what);
    if (isInteger(kind) && v != std::floor(v)) notA("an integer", token, what);
    return v;
  }

  [[noreturn, gnu::noinline, gnu::cold]] void notA(const char* expected, std::string_view token, const Record& what) const {
    fail(at(line_) + "expected " + expected + " in " + what.describe() + ", found '" + std::string(token.substr(0, 32)) + "'");
  }

  std::string_view body_;
  Format format_;
  bool swap_;
  std::size_t pos_ = 0;
  int line_;
};

// Reads record `what` of an element this reader does not keep (or a list it does not use).
void skipList(Values& values, const Property& p, const Record& what) {
  const double count = values.listLength(p, what);
  for (double k = 0; k < count; ++k) values.next(p.kind, what);
}

void readVertex(Values& values, const Layout& layout, const Record& what, std::vector<double>& item, PlyMesh& mesh) {
  const std::vector<Property>& properties = what.element->properties;
  for (std::size_t k = 0; k < properties.size(); ++k) {
    if (properties[k].countKind) skipList(values, properties[k], what);
    else item[k] = values.next(properties[k].kind, what);
  }
  const glm::dvec3 position(item[layout.slot[X]], item[layout.slot[Y]], item[layout.slot[Z]]);
  if (!std::isfinite(position.x) || !std::isfinite(position.y) || !std::isfinite(position.z))
    fail(values.where() + ": vertex " + std::to_string(what.index) + " has a coordinate that is not a finite number");
  mesh.vertices.push_back(position);
  if (layout.normals)
    mesh.normals.emplace_back(item[layout.slot[NX]], item[layout.slot[NY]], item[layout.slot[NZ]]);
  if (layout.texCoords) mesh.texCoords.emplace_back(item[layout.slot[U]], item[layout.slot[V]]);
  if (layout.colors)
    mesh.colors.push_back(glm::vec3(item[layout.slot[R]], item[layout.slot[G]], item[layout.slot[B]]) *
                          static_cast<float>(layout.colorScale));
}

[[noreturn, gnu::noinline, gnu::cold]] void badIndex(const Values& values, const Record& what, double i,
                                                     std::uint64_t vertexCount) {
  fail(values.where() + ": face " + std::to_string(what.index) + " uses vertex " + std::to_string(static_cast<long long>(i)) +
       ", but the file has " + std::to_string(vertexCount) + " vertices (indices 0.." +
       std::to_string(static_cast<long long>(vertexCount) - 1) + ")");
}

// The face's index list, each index checked against the vertices as it is read, split into a fan.
void readPolygon(Values& values, const Property& list, const Record& what, std::uint64_t vertexCount,
                 std::vector<std::uint32_t>& corners, PlyMesh& mesh) {
  const double count = values.listLength(list, what);
  corners.clear();
  for (double k = 0; k < count; ++k) {
    const double i = values.next(list.kind, what);
    if (!(i >= 0.0) || i >= static_cast<double>(vertexCount) || i != std::floor(i)) badIndex(values, what, i, vertexCount);
    corners.push_back(static_cast<std::uint32_t>(i));
  }
  if (corners.size() < 3) {
    ++mesh.skippedFaces;
    return;
  }
  if (mesh.triangles.size() + corners.size() > static_cast<std::size_t>(UINT32_MAX / 2)) fail("too many triangles");
  for (std::size_t k = 1; k + 1 < corners.size(); ++k) mesh.triangles.push_back(Triangle{{corners[0], corners[k], corners[k + 1]}});
}

// A triangle strip's index list; -1 ends one strip and starts the next. Every other triangle is flipped so that all
// keep the strip's winding; triangles with a repeated corner (the strips' joins) are left out.
void readStrip(Values& values, const Property& list, const Record& what, std::uint64_t vertexCount,
               std::vector<std::uint32_t>& corners, PlyMesh& mesh) {
  const double count = values.listLength(list, what);
  corners.clear();
  for (double k = 0; k <= count; ++k) {
    const double i = k < count ? values.next(list.kind, what) : -1.0;
    if (i == -1.0) {
      for (std::size_t c = 2; c < corners.size(); ++c) {
        const std::uint32_t a = corners[c - 2], b = corners[c - 1], d = corners[c];
        if (a == b || b == d || a == d) continue;
        if (mesh.triangles.size() >= static_cast<std::size_t>(UINT32_MAX / 2)) fail("too many triangles");
        mesh.triangles.push_back(c % 2 == 0 ? Triangle{{a, b, d}} : Triangle{{b, a, d}});
      }
      corners.clear();
      continue;
    }
    if (!(i >= 0.0) || i >= static_cast<double>(vertexCount) || i != std::floor(i)) badIndex(values, what, i, vertexCount);
    corners.push_back(static_cast<std::uint32_t>(i));
  }
}

void readRecords(const Header& header, const Layout& layout, std::string_view body, PlyMesh& mesh) {
  Values values(body, header.format, header.bodyLine);
  const std::uint64_t vertexCount = layout.vertex->count;
  std::vector<double> item(layout.vertex->properties.size());
  std::vector<std::uint32_t> corners;
  mesh.vertices.reserve(vertexCount);
  if (layout.normals) mesh.normals.reserve(vertexCount);
  if (layout.texCoords) mesh.texCoords.reserve(vertexCount);
  if (layout.colors) mesh.colors.reserve(vertexCount);
  // No more than the file could hold, whatever the count says.
  mesh.triangles.reserve(std::min<std::uint64_t>(layout.face->count, body.size() / 4));
  for (const Element& e : header.elements) {
    if (e.properties.empty()) continue;  // nothing to read, whatever the count
    for (std::uint64_t r = 0; r < e.count; ++r) {
      const Record what{&e, r};
      if (&e == layout.vertex) {
        readVertex(values, layout, what, item, mesh);
        values.endRecord();
        continue;
      }
      for (std::size_t k = 0; k < e.properties.size(); ++k) {
        const Property& p = e.properties[k];
        if (&e == layout.face && k == layout.indexList) {
          if (layout.strips) readStrip(values, p, what, vertexCount, corners, mesh);
          else readPolygon(values, p, what, vertexCount, corners, mesh);
        }
        else if (p.countKind) skipList(values, p, what);
        else values.next(p.kind, what);
      }
      values.endRecord();
    }
  }
}

}  // namespace

PlyMesh parsePly(std::string_view bytes) {
  const Header header = parseHeader(bytes);
  const Layout layout = layoutOf(header);
  const std::string_view body = bytes.substr(header.bodyStart);
  checkCounts(header, body.size());
  if (layout.vertex->count > static_cast<std::uint64_t>(INT32_MAX)) fail("the file declares too many vertices");
  PlyMesh mesh;
  readRecords(header, layout, body, mesh);
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
