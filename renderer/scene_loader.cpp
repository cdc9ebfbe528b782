// Reading a CSE 461 PA1 scene: repair pass, tinyxml2, then a case-insensitive walk that fills Scene.
// Every message a user can meet is listed in docs/scene-format-loading.md; keep the two in step.

#include "rayview/scene_loader.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string_view>
#include <unordered_map>

#include <glm/geometric.hpp>
#include <tinyxml2.h>

#include "number_list.h"
#include "texture_image.h"
#include "xml_repair.h"

namespace rayview {

namespace {

namespace fs = std::filesystem;
using detail::NumberStatus;
using tinyxml2::XMLElement;
using tinyxml2::XMLNode;

// --- limits (SPEC section 2: refuse up front what cannot fit) ---
constexpr std::int64_t kMaxRayDepthLimit = 1000000;
// 16384 x 16384: with a 16-byte-per-pixel accumulation buffer this is a 4 GiB framebuffer.
constexpr std::int64_t kMaxImagePixels = 1LL << 28;
constexpr std::uintmax_t kMaxFileBytes = (1ULL << 31) - 1;  // tinyxml2 and line numbers use int

// --- element names ---
enum class Tag {
  Unknown, Scene, MaxRayTraceDepth, Background, ShadowRayEpsilon, Camera, Position, Gaze, Up, NearPlane,
  NearDistance, ImageResolution, Lights, AmbientLight, PointLight, Intensity, TriangularLight, Vertex1,
  Vertex2, Vertex3, Materials, Material, Ambient, Diffuse, Specular, PhongExponent, MirrorReflectance,
  TextureFactor, VertexData, TextureData, NormalData, TextureImage, Objects, Mesh, MaterialId, Faces,
  Count
};

struct TagName {
  std::string_view name;
  Tag tag;
};

constexpr TagName kTagNames[] = {
    {"scene", Tag::Scene}, {"maxraytracedepth", Tag::MaxRayTraceDepth}, {"background", Tag::Background},
    {"shadowrayepsilon", Tag::ShadowRayEpsilon}, {"camera", Tag::Camera}, {"position", Tag::Position},
    {"gaze", Tag::Gaze}, {"up", Tag::Up}, {"nearplane", Tag::NearPlane}, {"neardistance", Tag::NearDistance},
    {"imageresolution", Tag::ImageResolution}, {"lights", Tag::Lights}, {"ambientlight", Tag::AmbientLight},
    {"pointlight", Tag::PointLight}, {"intensity", Tag::Intensity}, {"triangularlight", Tag::TriangularLight},
    {"vertex1", Tag::Vertex1}, {"vertex2", Tag::Vertex2}, {"vertex3", Tag::Vertex3},
    {"materials", Tag::Materials}, {"material", Tag::Material}, {"ambient", Tag::Ambient},
    {"diffuse", Tag::Diffuse}, {"specular", Tag::Specular}, {"phongexponent", Tag::PhongExponent},
    {"mirrorreflectance", Tag::MirrorReflectance}, {"texturefactor", Tag::TextureFactor},
    {"vertexdata", Tag::VertexData}, {"texturedata", Tag::TextureData}, {"normaldata", Tag::NormalData},
    {"textureimage", Tag::TextureImage}, {"objects", Tag::Objects}, {"mesh", Tag::Mesh},
    {"materialid", Tag::MaterialId}, {"faces", Tag::Faces},
};

std::string toLower(std::string_view s) {
  std::string out(s);
  for (char& c : out)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return out;
}

std::string_view tagName(Tag tag) {
  for (const TagName& t : kTagNames)
    if (t.tag == tag) return t.name;
  return "?";
}

// A token as it appears in a message: quoted, shortened.
std::string quoted(std::string_view token) {
  constexpr std::size_t kMax = 32;
  std::string out = "'";
  out.append(token.substr(0, kMax));
  if (token.size() > kMax) out += "...";
  return out + "'";
}

std::string plural(std::size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

// The text of an element, in pieces (text nodes split by comments), each with its line.
struct Piece {
  std::string_view text;
  int line;  // tinyxml2 reports a text node at its first non-space character
};

struct FaceCorner {
  std::int64_t v, t, n;  // -1 when absent
};

struct PendingMesh {
  std::string id;
  int line = 0;
  std::string materialId;
  int materialIdLine = 0;
  const XMLElement* faces = nullptr;
  std::uint32_t firstTriangle = 0;
  std::uint32_t triangleCount = 0;
};

struct IndexRange {
  std::int64_t min = INT64_MAX, max = -1;
  int firstZeroLine = 0;
  void add(std::int64_t i, int line) {
    if (i < 0) return;
    if (i == 0 && min != 0) firstZeroLine = line;
    min = std::min(min, i);
    max = std::max(max, i);
  }
  bool any() const { return max >= 0; }
};

class Loader {
 public:
  Loader(const std::string& file, fs::path baseDirectory, const LoadOptions& options)
      : file_(file), baseDirectory_(std::move(baseDirectory)), options_(options) {}

  LoadedScene load(std::string_view text) {
    detail::RepairedXml repaired = detail::repairXml(text, file_, options_.strict);
    for (Diagnostic& d : repaired.repairs) result_.warnings.push_back(std::move(d));
    std::string_view xml = repaired.changed ? std::string_view(repaired.text) : text;

    tinyxml2::XMLDocument doc(true, tinyxml2::PRESERVE_WHITESPACE);
    if (doc.Parse(xml.data(), xml.size()) != tinyxml2::XML_SUCCESS) xmlError(doc);

    const XMLElement* root = doc.RootElement();
    if (!root) fail(0, "no <scene> element: the file has no elements");
    detectCeng477(root);
    if (!isName(root, "scene"))
      fail(root->GetLineNum(), "the root element is <" + std::string(root->Name()) + ">, expected <scene>");
    for (const XMLNode* node = root->NextSibling(); node; node = node->NextSibling()) {
      if (const XMLElement* extra = node->ToElement()) unknownElement(extra, "after </scene>");
      if (const tinyxml2::XMLText* text = node->ToText()) strayText(text);
    }
    for (const XMLNode* node = doc.FirstChild(); node && node != root; node = node->NextSibling())
      if (const tinyxml2::XMLText* text = node->ToText()) strayText(text);

    readScene(root);
    finish(root);
    std::stable_sort(result_.warnings.begin(), result_.warnings.end(),
                     [](const Diagnostic& a, const Diagnostic& b) { return a.where.line < b.where.line; });
    return std::move(result_);
  }

 private:
  // ---------------------------------------------------------------- messages
  [[noreturn]] void fail(int line, const std::string& message) { throwSceneError({file_, line}, message); }

  // Warnings with the same text are reported once, at the first line, with a count.
  void warn(int line, const std::string& message) {
    auto [it, inserted] = warningIndex_.emplace(message, result_.warnings.size());
    if (!inserted) {
      ++warningCounts_[it->second];
      return;
    }
    result_.warnings.push_back(Diagnostic{Severity::Warning, {file_, line}, message});
    warningCounts_.push_back(1);
  }

  // Something the format does not allow but that we can read anyway: an error in strict mode.
  void nonconforming(int line, const std::string& message) {
    if (options_.strict) fail(line, message + " [strict mode]");
    warn(line, message);
  }

  void xmlError(const tinyxml2::XMLDocument& doc) {
    std::string what;
    switch (doc.ErrorID()) {
      case tinyxml2::XML_ERROR_EMPTY_DOCUMENT: fail(0, "no <scene> element: the file is empty");
      case tinyxml2::XML_ERROR_PARSING_ATTRIBUTE: what = "malformed attribute"; break;
      case tinyxml2::XML_ERROR_PARSING_ELEMENT: what = "malformed element"; break;
      case tinyxml2::XML_ERROR_MISMATCHED_ELEMENT: what = "mismatched closing tag"; break;
      case tinyxml2::XML_ERROR_PARSING_TEXT: what = "malformed text (a literal '<' or '&' must be escaped)"; break;
      case tinyxml2::XML_ERROR_PARSING_COMMENT: what = "malformed comment"; break;
      case tinyxml2::XML_ERROR_PARSING_DECLARATION: what = "malformed <?...?> declaration"; break;
      case tinyxml2::XML_ERROR_PARSING_CDATA: what = "malformed CDATA section"; break;
      case tinyxml2::XML_ERROR_PARSING_UNKNOWN: what = "malformed <!...> declaration"; break;
      case tinyxml2::XML_ELEMENT_DEPTH_EXCEEDED: what = "elements nested too deeply"; break;
      default: what = doc.ErrorName(); break;
    }
    fail(doc.ErrorLineNum(), "XML syntax error: " + what);
  }

  // Built with append: GCC 12 warns (-Wrestrict, a false positive) on "<" + std::string(...).
  static std::string elementName(const XMLElement* e) {
    std::string s(1, '<');
    s.append(e->Name());
    s.push_back('>');
    return s;
  }

  // ---------------------------------------------------------------- names
  static bool isName(const XMLElement* e, std::string_view lowercase) {
    return detail::equalsIgnoreCase(e->Name(), lowercase);
  }

  // The element's tag, after case folding and aliases (an alias is reported once per spelling).
  Tag identify(const XMLElement* e) {
    const std::string name = toLower(e->Name());
    std::string_view canonical = name;
    std::string_view alias = detail::canonicalAlias(name);
    if (!alias.empty()) {
      canonical = alias;
      const std::string written = elementName(e);
      if (name == "backgroundcolor")
        nonconforming(e->GetLineNum(), written + " read as <background> (the handout example's spelling; the format's name is <background>)");
      else
        nonconforming(e->GetLineNum(), written + " read as <" + std::string(alias) + "> (misspelled element name)");
    }
    for (const TagName& t : kTagNames)
      if (t.name == canonical) return t.tag;
    return Tag::Unknown;
  }

  void unknownElement(const XMLElement* e, const std::string& where) {
    const std::string name = toLower(e->Name());
    std::string message;
    bool known = false;
    for (const TagName& t : kTagNames) known = known || t.name == name || t.name == detail::canonicalAlias(name);
    if (known)
      message = "element " + elementName(e) + " is not expected " + where + "; ignored";
    else
      message = "unknown element " + elementName(e) + " ignored";
    if (where == "inside <objects>" && !known) message += " (only <mesh> objects are part of the format)";
    nonconforming(e->GetLineNum(), message);
  }

  void strayText(const tinyxml2::XMLText* text) {
    std::string_view value = text->Value();
    std::size_t b = 0, e = value.size();
    while (b < e && detail::isXmlSpace(value[b])) ++b;
    while (e > b && detail::isXmlSpace(value[e - 1])) --e;
    if (b == e) return;
    nonconforming(text->GetLineNum(), "stray text " + quoted(value.substr(b, e - b)) + " ignored");
  }

  // Calls `onElement(child, tag)` for each child element, warning about text and (through the callback
  // returning false) unexpected elements. Checks that single-valued children appear once.
  template <class F>
  void forEachChild(const XMLElement* parent, const std::string& where, F&& onElement) {
    int seen[static_cast<int>(Tag::Count)] = {};
    for (const XMLNode* node = parent->FirstChild(); node; node = node->NextSibling()) {
      if (const tinyxml2::XMLText* text = node->ToText()) {
        strayText(text);
        continue;
      }
      const XMLElement* child = node->ToElement();
      if (!child) continue;  // comments, declarations
      const Tag tag = identify(child);
      if (tag == Tag::Unknown) {
        unknownElement(child, where);
        continue;
      }
      const bool repeatable = tag == Tag::PointLight || tag == Tag::TriangularLight || tag == Tag::Material ||
                              tag == Tag::Mesh || tag == Tag::Lights || tag == Tag::Materials || tag == Tag::Objects;
      int& first = seen[static_cast<int>(tag)];
      if (first != 0 && !repeatable)
        fail(child->GetLineNum(), "duplicate " + elementName(child) + " " + where + " (the first is at line " +
                                      std::to_string(first) + ")");
      if (first == 0) first = child->GetLineNum();
      if (!onElement(child, tag)) unknownElement(child, where);
    }
  }

  // ---------------------------------------------------------------- text and numbers
  std::vector<Piece> textOf(const XMLElement* e) {
    std::vector<Piece> pieces;
    for (const XMLNode* node = e->FirstChild(); node; node = node->NextSibling()) {
      if (const tinyxml2::XMLText* text = node->ToText()) {
        pieces.push_back({text->Value(), text->GetLineNum()});
      } else if (const XMLElement* child = node->ToElement()) {
        unknownElement(child, "inside " + elementName(e));
      }
    }
    return pieces;
  }

  static int lineIn(const Piece& piece, const char* p) {
    const char* first = piece.text.data();
    const char* end = piece.text.data() + piece.text.size();
    while (first < end && detail::isXmlSpace(*first)) ++first;
    return piece.line + (p > first ? detail::countNewlines(first, p) : 0);
  }

  // Reads every number of an element into `out` (appending). `asFloat` also refuses values beyond float.
  void readNumbers(const XMLElement* e, std::vector<double>& out, bool asFloat) {
    const std::vector<Piece> pieces = textOf(e);
    for (const Piece& piece : pieces) {
      detail::TokenScanner scanner(piece.text);
      double value = 0.0;
      NumberStatus status = NumberStatus::Ok;
      std::string_view token;
      bool glued = false;
      while (scanner.nextNumber(value, status, token, glued)) {
        if (status == NumberStatus::NotANumber)
          fail(lineIn(piece, token.data()), elementName(e) + ": expected a number, found " + quoted(token));
        if (status == NumberStatus::NotFinite || (asFloat && std::fabs(value) > FLT_MAX))
          fail(lineIn(piece, token.data()), elementName(e) + ": " + quoted(token) + " is not a finite number" +
                                                (status == NumberStatus::Ok ? " in single precision" : ""));
        if (glued) {
          const char* tokenEnd = scanner.position();
          while (tokenEnd < piece.text.data() + piece.text.size() && !detail::isXmlSpace(*tokenEnd)) ++tokenEnd;
          nonconforming(lineIn(piece, token.data()),
                        elementName(e) + ": numbers not separated by whitespace in " +
                            quoted(std::string_view(token.data(), static_cast<std::size_t>(tokenEnd - token.data()))) +
                            " (read as separate numbers)");
        }
        out.push_back(value);
      }
    }
  }

  // Exactly `count` finite numbers.
  void readFixed(const XMLElement* e, std::size_t count, double* values, bool asFloat) {
    std::vector<double> numbers;
    readNumbers(e, numbers, asFloat);
    if (numbers.size() != count)
      fail(e->GetLineNum(), elementName(e) + ": expected " + plural(count, "number", "numbers") + ", found " +
                                std::to_string(numbers.size()));
    std::copy(numbers.begin(), numbers.end(), values);
  }

  glm::dvec3 readPoint(const XMLElement* e) {
    double v[3];
    readFixed(e, 3, v, false);
    return {v[0], v[1], v[2]};
  }
  Color readColor(const XMLElement* e) {
    double v[3];
    readFixed(e, 3, v, true);
    return Color(static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]));
  }
  double readScalar(const XMLElement* e, bool asFloat) {
    double v;
    readFixed(e, 1, &v, asFloat);
    return v;
  }

  // Exactly `count` integers; `what` describes them for the message ("a non-negative integer").
  void readIntegers(const XMLElement* e, std::size_t count, std::int64_t* values, std::int64_t minimum,
                    const std::string& what) {
    const std::vector<Piece> pieces = textOf(e);
    std::size_t found = 0;
    for (const Piece& piece : pieces) {
      detail::TokenScanner scanner(piece.text);
      std::int64_t value = 0;
      NumberStatus status = NumberStatus::Ok;
      std::string_view token;
      while (scanner.nextInteger(value, status, token)) {
        if (status != NumberStatus::Ok || value < minimum)
          fail(lineIn(piece, token.data()), elementName(e) + ": expected " + what + ", found " + quoted(token));
        if (found < count) values[found] = value;
        ++found;
      }
    }
    if (found != count)
      fail(e->GetLineNum(), elementName(e) + ": expected " + what + ", found " + plural(found, "number", "numbers"));
  }

  std::string attribute(const XMLElement* e, std::string_view name) {
    for (const tinyxml2::XMLAttribute* a = e->FirstAttribute(); a; a = a->Next())
      if (detail::equalsIgnoreCase(a->Name(), name)) return a->Value();
    return {};
  }
  bool hasAttribute(const XMLElement* e, std::string_view name) {
    for (const tinyxml2::XMLAttribute* a = e->FirstAttribute(); a; a = a->Next())
      if (detail::equalsIgnoreCase(a->Name(), name)) return true;
    return false;
  }

  std::string trimmedText(const XMLElement* e) {
    std::string text;
    for (const Piece& piece : textOf(e)) text.append(piece.text);
    std::size_t b = text.find_first_not_of(" \t\r\n");
    if (b == std::string::npos) return {};
    std::size_t end = text.find_last_not_of(" \t\r\n");
    return text.substr(b, end - b + 1);
  }

  // ---------------------------------------------------------------- the METU CENG477 format
  void detectCeng477(const XMLElement* root) {
    if (!isName(root, "scene")) return;
    for (const XMLElement* child = root->FirstChildElement(); child; child = child->NextSiblingElement())
      if (isName(child, "cameras"))
        fail(child->GetLineNum(),
             "this looks like a METU CENG477 scene (<Cameras>, <MaxRecursionDepth>, <AmbientReflectance>...), not the "
             "CSE 461 PA1 format: it has <" + std::string(child->Name()) + "> where the format has one <camera>; "
             "convert it to the CSE 461 format first");
  }

  // ---------------------------------------------------------------- the scene
  void readScene(const XMLElement* root) {
    Scene& scene = result_.scene;
    forEachChild(root, "inside <scene>", [&](const XMLElement* e, Tag tag) {
      switch (tag) {
        case Tag::MaxRayTraceDepth: {
          std::int64_t depth = 0;
          readIntegers(e, 1, &depth, 0, "a non-negative integer");
          if (depth > kMaxRayDepthLimit)
            fail(e->GetLineNum(), elementName(e) + ": " + std::to_string(depth) + " is above the limit of " +
                                      std::to_string(kMaxRayDepthLimit));
          scene.maxRayDepth = static_cast<int>(depth);
          haveDepth_ = true;
          return true;
        }
        case Tag::Background:
          scene.background = readColor(e);
          haveBackground_ = true;
          return true;
        case Tag::ShadowRayEpsilon: {
          double epsilon = readScalar(e, false);
          if (epsilon < 0.0) fail(e->GetLineNum(), elementName(e) + ": must be >= 0, found " + trimmedText(e));
          scene.shadowRayEpsilon = epsilon;
          return true;
        }
        case Tag::Camera: readCamera(e); return true;
        case Tag::Lights: readLights(e); return true;
        case Tag::Materials: readMaterials(e); return true;
        case Tag::VertexData: readVertices(e); return true;
        case Tag::TextureData: readTexCoords(e); return true;
        case Tag::NormalData: readNormals(e); return true;
        case Tag::TextureImage:
          scene.textureImage = trimmedText(e);
          textureImageLine_ = e->GetLineNum();
          return true;
        case Tag::Objects: readObjects(e); return true;
        default: return false;
      }
    });
  }

  void readCamera(const XMLElement* cameraElement) {
    Camera& camera = result_.scene.camera;
    const int line = cameraElement->GetLineNum();
    cameraLine_ = line;
    unsigned have = 0;
    auto bit = [](Tag t) { return 1u << (static_cast<unsigned>(t) - static_cast<unsigned>(Tag::Position)); };
    forEachChild(cameraElement, "inside <camera>", [&](const XMLElement* e, Tag tag) {
      switch (tag) {
        case Tag::Position: camera.position = readPoint(e); break;
        case Tag::Gaze: camera.gaze = readPoint(e); break;
        case Tag::Up: camera.up = readPoint(e); break;
        case Tag::NearPlane: {
          double v[4];
          readFixed(e, 4, v, false);
          camera.left = v[0], camera.right = v[1], camera.bottom = v[2], camera.top = v[3];
          break;
        }
        case Tag::NearDistance: camera.nearDistance = readScalar(e, false); break;
        case Tag::ImageResolution: {
          std::int64_t v[2];
          readIntegers(e, 2, v, INT64_MIN, "2 integers (nx ny)");
          if (v[0] > 0 && v[1] > 0 && (v[0] > kMaxImagePixels || v[1] > kMaxImagePixels || v[0] * v[1] > kMaxImagePixels))
            fail(e->GetLineNum(), elementName(e) + ": " + std::to_string(v[0]) + " x " + std::to_string(v[1]) +
                                      " pixels is too large (the limit is " + std::to_string(kMaxImagePixels) +
                                      " pixels, 16384 x 16384)");
          camera.width = static_cast<int>(std::clamp<std::int64_t>(v[0], INT32_MIN, INT32_MAX));
          camera.height = static_cast<int>(std::clamp<std::int64_t>(v[1], INT32_MIN, INT32_MAX));
          break;
        }
        default: return false;
      }
      have |= bit(tag);
      return true;
    });
    for (Tag t : {Tag::Position, Tag::Gaze, Tag::Up, Tag::NearPlane, Tag::NearDistance, Tag::ImageResolution})
      if (!(have & bit(t))) fail(line, "<camera> has no <" + std::string(tagName(t)) + ">");

    // SPEC section 3: a camera that cannot make an image.
    if (glm::length(camera.gaze) == 0.0) fail(line, "camera: <gaze> is the zero vector");
    if (glm::length(camera.up) == 0.0) fail(line, "camera: <up> is the zero vector");
    const glm::dvec3 side = glm::cross(glm::normalize(camera.gaze), glm::normalize(camera.up));
    if (!(glm::length(side) > 1e-9)) fail(line, "camera: <up> is parallel to <gaze>");
    if (camera.left == camera.right)
      fail(line, "camera: <nearplane> left and right are equal (" + trimmedNumber(camera.left) + "), the image has no width");
    if (camera.bottom == camera.top)
      fail(line, "camera: <nearplane> bottom and top are equal (" + trimmedNumber(camera.bottom) + "), the image has no height");
    if (!(camera.nearDistance > 0.0))
      fail(line, "camera: <neardistance> must be positive, found " + trimmedNumber(camera.nearDistance));
    if (camera.width <= 0 || camera.height <= 0)
      fail(line, "camera: <imageresolution> must be positive, found " + std::to_string(camera.width) + " x " +
                     std::to_string(camera.height));
  }

  static std::string trimmedNumber(double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%g", v);
    return buffer;
  }

  void readLights(const XMLElement* lights) {
    Scene& scene = result_.scene;
    forEachChild(lights, "inside <lights>", [&](const XMLElement* e, Tag tag) {
      switch (tag) {
        case Tag::AmbientLight:
          scene.ambientLight = readColor(e);
          haveAmbient_ = true;
          return true;
        case Tag::PointLight: {
          PointLight light;
          light.id = attribute(e, "id");
          bool position = false, intensity = false;
          forEachChild(e, "inside " + elementName(e), [&](const XMLElement* c, Tag t) {
            if (t == Tag::Position) light.position = readPoint(c), position = true;
            else if (t == Tag::Intensity) light.intensity = readColor(c), intensity = true;
            else return false;
            return true;
          });
          if (!position) fail(e->GetLineNum(), describe(e) + " has no <position>");
          if (!intensity) fail(e->GetLineNum(), describe(e) + " has no <intensity>");
          scene.pointLights.push_back(std::move(light));
          return true;
        }
        case Tag::TriangularLight: {
          TriangularLight light;
          light.id = attribute(e, "id");
          unsigned have = 0;
          forEachChild(e, "inside " + elementName(e), [&](const XMLElement* c, Tag t) {
            if (t == Tag::Vertex1) light.vertex1 = readPoint(c), have |= 1;
            else if (t == Tag::Vertex2) light.vertex2 = readPoint(c), have |= 2;
            else if (t == Tag::Vertex3) light.vertex3 = readPoint(c), have |= 4;
            else if (t == Tag::Intensity) light.intensity = readColor(c), have |= 8;
            else return false;
            return true;
          });
          const char* names[] = {"<vertex1>", "<vertex2>", "<vertex3>", "<intensity>"};
          for (int i = 0; i < 4; ++i)
            if (!(have & (1u << i))) fail(e->GetLineNum(), describe(e) + " has no " + names[i]);
          scene.triangularLights.push_back(std::move(light));
          return true;
        }
        default: return false;
      }
    });
  }

  // <pointlight id="1"> as written, for messages.
  std::string describe(const XMLElement* e) {
    if (!hasAttribute(e, "id")) return elementName(e);
    std::string s = elementName(e);
    s.pop_back();
    return s + " id=\"" + attribute(e, "id") + "\">";
  }

  void readMaterials(const XMLElement* materials) {
    Scene& scene = result_.scene;
    forEachChild(materials, "inside <materials>", [&](const XMLElement* e, Tag tag) {
      if (tag != Tag::Material) return false;
      if (!hasAttribute(e, "id")) fail(e->GetLineNum(), elementName(e) + " has no id attribute");
      Material material;
      material.id = attribute(e, "id");
      auto [it, inserted] = materialLines_.emplace(material.id, e->GetLineNum());
      if (!inserted)
        fail(e->GetLineNum(), "duplicate material id \"" + material.id + "\" (the first is at line " +
                                  std::to_string(it->second) + ")");
      unsigned have = 0;
      forEachChild(e, "inside " + elementName(e), [&](const XMLElement* c, Tag t) {
        switch (t) {
          case Tag::Ambient: material.ambient = readColor(c), have |= 1; break;
          case Tag::Diffuse: material.diffuse = readColor(c), have |= 2; break;
          case Tag::Specular: material.specular = readColor(c), have |= 4; break;
          case Tag::PhongExponent: {
            double p = readScalar(c, true);
            if (p < 0.0) fail(c->GetLineNum(), elementName(c) + ": must be >= 0, found " + trimmedText(c));
            material.phongExponent = static_cast<float>(p);
            have |= 8;
            break;
          }
          case Tag::MirrorReflectance: material.mirror = readColor(c), have |= 16; break;
          case Tag::TextureFactor: material.textureFactor = static_cast<float>(readScalar(c, true)); break;
          default: return false;
        }
        return true;
      });
      const char* names[] = {"<ambient>", "<diffuse>", "<specular>", "<phongexponent>"};
      for (int i = 0; i < 4; ++i)
        if (!(have & (1u << i))) fail(e->GetLineNum(), describe(e) + " has no " + names[i]);
      if (!(have & 16))
        warn(e->GetLineNum(), describe(e) + " has no <mirrorreflectance>; using 0 0 0 (not a mirror)");
      materialIndex_.emplace(material.id, static_cast<std::uint32_t>(scene.materials.size()));
      scene.materials.push_back(std::move(material));
      return true;
    });
  }

  // ---------------------------------------------------------------- geometry
  // Numbers of a big block straight into `out`, `stride` per item.
  void readBlock(const XMLElement* e, std::size_t stride, const char* itemName, std::vector<double>& numbers,
                 bool asFloat) {
    numbers.clear();
    std::size_t textSize = 0;
    for (const XMLNode* node = e->FirstChild(); node; node = node->NextSibling())
      if (node->ToText()) textSize += std::strlen(node->Value());
    numbers.reserve(textSize / 8 + 16);
    readNumbers(e, numbers, asFloat);
    if (numbers.size() % stride != 0)
      fail(e->GetLineNum(), elementName(e) + ": expected " + std::to_string(stride) + " numbers per " + itemName +
                                ", found " + std::to_string(numbers.size()) + " numbers (not a multiple of " +
                                std::to_string(stride) + ")");
    if (numbers.size() / stride > static_cast<std::size_t>(INT32_MAX))
      fail(e->GetLineNum(), elementName(e) + ": too many " + itemName + "s");
  }

  void readVertices(const XMLElement* e) {
    std::vector<double> numbers;
    readBlock(e, 3, "vertex", numbers, false);
    auto& vertices = result_.scene.vertices;
    vertices.resize(numbers.size() / 3);
    for (std::size_t i = 0; i < vertices.size(); ++i)
      vertices[i] = glm::dvec3(numbers[3 * i], numbers[3 * i + 1], numbers[3 * i + 2]);
  }
  void readTexCoords(const XMLElement* e) {
    std::vector<double> numbers;
    readBlock(e, 2, "texture coordinate", numbers, true);
    auto& uvs = result_.scene.texCoords;
    uvs.resize(numbers.size() / 2);
    for (std::size_t i = 0; i < uvs.size(); ++i)
      uvs[i] = glm::vec2(static_cast<float>(numbers[2 * i]), static_cast<float>(numbers[2 * i + 1]));
  }
  void readNormals(const XMLElement* e) {
    std::vector<double> numbers;
    readBlock(e, 3, "normal", numbers, true);
    auto& normals = result_.scene.normals;
    normals.resize(numbers.size() / 3);
    for (std::size_t i = 0; i < normals.size(); ++i)
      normals[i] = glm::vec3(static_cast<float>(numbers[3 * i]), static_cast<float>(numbers[3 * i + 1]),
                             static_cast<float>(numbers[3 * i + 2]));
  }

  void readObjects(const XMLElement* objects) {
    forEachChild(objects, "inside <objects>", [&](const XMLElement* e, Tag tag) {
      if (tag != Tag::Mesh) return false;
      PendingMesh mesh;
      mesh.id = attribute(e, "id");
      mesh.line = e->GetLineNum();
      bool haveMaterial = false;
      forEachChild(e, "inside " + elementName(e), [&](const XMLElement* c, Tag t) {
        if (t == Tag::MaterialId) {
          mesh.materialId = trimmedText(c);
          mesh.materialIdLine = c->GetLineNum();
          haveMaterial = true;
        } else if (t == Tag::Faces) {
          mesh.faces = c;
        } else {
          return false;
        }
        return true;
      });
      if (!haveMaterial) fail(mesh.line, describe(e) + " has no <materialid>");
      if (!mesh.faces) fail(mesh.line, describe(e) + " has no <faces>");
      readFaces(mesh);
      meshes_.push_back(std::move(mesh));
      return true;
    });
  }

  std::string meshName(const PendingMesh& mesh) const { return "mesh \"" + mesh.id + "\""; }

  // Face tokens: v, v/t, v//n or v/t/n; stored raw (file numbering) until the index base is known.
  void readFaces(PendingMesh& mesh) {
    const XMLElement* e = mesh.faces;
    std::vector<Triangle>& triangles = result_.scene.triangles;
    if (triangles.size() > static_cast<std::size_t>(UINT32_MAX / 2))
      fail(e->GetLineNum(), "too many triangles");
    mesh.firstTriangle = static_cast<std::uint32_t>(triangles.size());
    const std::vector<Piece> pieces = textOf(e);
    std::size_t textSize = 0;
    for (const Piece& piece : pieces) textSize += piece.text.size();
    triangles.reserve(triangles.size() + textSize / 8 + 1);

    FaceCorner corners[3];
    int cornerCount = 0;
    std::size_t indexCount = 0;
    for (const Piece& piece : pieces) {
      detail::TokenScanner scanner(piece.text);
      for (std::string_view token = scanner.nextToken(); !token.empty(); token = scanner.nextToken()) {
        FaceCorner& corner = corners[cornerCount];
        if (!parseCorner(token, corner)) {
          const int line = lineIn(piece, token.data());
          if (token.find_first_not_of("+-0123456789/") == std::string_view::npos && token.find('-') != token.npos)
            fail(line, meshName(mesh) + ": " + elementName(e) + ": face indices must be positive, found " + quoted(token));
          fail(line, meshName(mesh) + ": " + elementName(e) + ": expected a vertex index (v, v/t, v//n or v/t/n), found " +
                         quoted(token));
        }
        ++indexCount;
        if (++cornerCount < 3) continue;
        cornerCount = 0;
        if ((corners[0].t < 0) != (corners[1].t < 0) || (corners[0].t < 0) != (corners[2].t < 0) ||
            (corners[0].n < 0) != (corners[1].n < 0) || (corners[0].n < 0) != (corners[2].n < 0))
          fail(lineIn(piece, token.data()), meshName(mesh) + ": a face mixes index forms (v, v/t, v//n, v/t/n) in " +
                                                "its three corners; the last one is " + quoted(token));
        Triangle triangle;
        for (int k = 0; k < 3; ++k) {
          triangle.vertex[k] = static_cast<std::uint32_t>(corners[k].v);
          triangle.texCoord[k] = static_cast<std::int32_t>(corners[k].t);
          triangle.normal[k] = static_cast<std::int32_t>(corners[k].n);
        }
        const bool needLine = corners[0].v == 0 || corners[1].v == 0 || corners[2].v == 0 || corners[0].t == 0 ||
                              corners[1].t == 0 || corners[2].t == 0 || corners[0].n == 0 ||
                              corners[1].n == 0 || corners[2].n == 0;
        const int line = needLine ? lineIn(piece, token.data()) : 0;
        for (int k = 0; k < 3; ++k) {
          vertexRange_.add(corners[k].v, line);
          textureRange_.add(corners[k].t, line);
          normalRange_.add(corners[k].n, line);
        }
        triangles.push_back(triangle);
      }
    }
    if (cornerCount != 0)
      fail(e->GetLineNum(), meshName(mesh) + ": " + elementName(e) + " has " + std::to_string(indexCount) +
                                " vertex indices, not a multiple of 3");
    mesh.triangleCount = static_cast<std::uint32_t>(triangles.size() - mesh.firstTriangle);
  }

  static bool parseIndex(const char*& p, const char* end, std::int64_t& value) {
    auto [ptr, ec] = std::from_chars(p, end, value);
    if (ptr == p || ec != std::errc() || value < 0 || value > INT32_MAX) return false;
    p = ptr;
    return true;
  }

  static bool parseCorner(std::string_view token, FaceCorner& corner) {
    const char* p = token.data();
    const char* end = p + token.size();
    corner = {-1, -1, -1};
    if (!parseIndex(p, end, corner.v)) return false;
    if (p == end) return true;
    if (*p++ != '/') return false;
    if (p < end && *p != '/' && !parseIndex(p, end, corner.t)) return false;
    if (p == end) return corner.t >= 0;  // "v/" is not a form
    if (*p++ != '/') return false;
    if (!parseIndex(p, end, corner.n)) return false;
    return p == end;
  }

  // ---------------------------------------------------------------- after the walk
  void finish(const XMLElement* root) {
    const int rootLine = root->GetLineNum();
    if (cameraLine_ == 0) fail(rootLine, "no <camera> element");
    if (!haveDepth_) warn(rootLine, "no <maxraytracedepth>: using 0 (no mirror reflections)");
    if (!haveBackground_) warn(rootLine, "no <background>: using black (0 0 0)");
    if (!haveAmbient_) warn(rootLine, "no <ambientlight>: using black (0 0 0)");

    for (PendingMesh& mesh : meshes_) {
      auto it = materialIndex_.find(mesh.materialId);
      if (it == materialIndex_.end())
        fail(mesh.materialIdLine, meshName(mesh) + ": material \"" + mesh.materialId + "\" is not defined" +
                                      definedMaterials());
    }
    resolveIndices(rootLine);
    loadTexture();

    for (std::size_t i = 0; i < result_.warnings.size(); ++i)
      if (warningCounts_.size() > i && warningCounts_[i] > 1)
        result_.warnings[i].message += " (" + std::to_string(warningCounts_[i]) + " times; the first is shown)";
  }

  std::string definedMaterials() const {
    const auto& materials = result_.scene.materials;
    if (materials.empty()) return " (the file defines no materials)";
    std::string list = " (defined:";
    for (std::size_t i = 0; i < materials.size() && i < 8; ++i) list += " \"" + materials[i].id + "\"";
    if (materials.size() > 8) list += " ...";
    return list + ")";
  }

  // 1-based (the handout) unless the indices of a kind contain 0 and never reach the count (SPEC section 2).
  void resolveIndices(int rootLine) {
    Scene& scene = result_.scene;
    const std::int64_t counts[3] = {static_cast<std::int64_t>(scene.vertices.size()),
                                    static_cast<std::int64_t>(scene.texCoords.size()),
                                    static_cast<std::int64_t>(scene.normals.size())};
    const IndexRange* ranges[3] = {&vertexRange_, &textureRange_, &normalRange_};
    const char* kinds[3] = {"vertex", "texture", "normal"};
    std::int64_t base[3] = {1, 1, 1};
    std::string zeroBased;
    int zeroLine = 0;
    for (int k = 0; k < 3; ++k) {
      if (ranges[k]->any() && ranges[k]->min == 0 && ranges[k]->max < counts[k]) {
        base[k] = 0;
        zeroBased += zeroBased.empty() ? kinds[k] : std::string(", ") + kinds[k];
        if (zeroLine == 0 || ranges[k]->firstZeroLine < zeroLine) zeroLine = ranges[k]->firstZeroLine;
      }
    }
    if (!zeroBased.empty())
      nonconforming(zeroLine ? zeroLine : rootLine,
                    "face indices are 0-based (" + zeroBased + " indices include 0 and never reach the count); "
                    "read as 0-based, the format's indices start at 1");

    std::vector<Triangle>& triangles = scene.triangles;
    std::size_t kept = 0;
    for (std::uint32_t m = 0; m < meshes_.size(); ++m) {
      PendingMesh& pending = meshes_[m];
      const std::uint32_t material = materialIndex_.at(pending.materialId);
      const std::uint32_t first = static_cast<std::uint32_t>(kept);
      std::size_t degenerate = 0;
      for (std::uint32_t i = 0; i < pending.triangleCount; ++i) {
        Triangle t = triangles[pending.firstTriangle + i];
        for (int c = 0; c < 3; ++c) {
          const std::int64_t raw[3] = {t.vertex[c], t.texCoord[c], t.normal[c]};
          for (int k = 0; k < 3; ++k) {
            if (k > 0 && raw[k] < 0) continue;
            const std::int64_t index = raw[k] - base[k];
            if (index < 0 || index >= counts[k]) indexOutOfRange(pending, i * 3 + c, kinds[k], raw[k], base[k], counts[k]);
          }
          t.vertex[c] = static_cast<std::uint32_t>(raw[0] - base[0]);
          if (raw[1] >= 0) t.texCoord[c] = static_cast<std::int32_t>(raw[1] - base[1]);
          if (raw[2] >= 0) t.normal[c] = static_cast<std::int32_t>(raw[2] - base[2]);
        }
        if (isDegenerate(t)) {
          ++degenerate;
          continue;
        }
        t.material = material;
        t.mesh = m;
        triangles[kept++] = t;
      }
      if (degenerate > 0)
        warn(pending.line, meshName(pending) + ": " + plural(degenerate, "degenerate triangle", "degenerate triangles") +
                               " skipped (zero area or a repeated vertex)");
      scene.meshes.push_back(Mesh{pending.id, material, first, static_cast<std::uint32_t>(kept - first)});
    }
    triangles.resize(kept);
    triangles.shrink_to_fit();
    warnAboutDuplicatedFaces();
  }

  // Faces listed twice (same three vertices, any order or winding) are coincident surfaces: which one a
  // ray sees is a tie, which rayview gives to the face listed first. Real files do this (a wall written once
  // as a mirror and once as a colour), and the picture then depends on that rule: say so.
  void warnAboutDuplicatedFaces() {
    const std::vector<Triangle>& triangles = result_.scene.triangles;
    std::vector<std::array<std::uint32_t, 4>> keys(triangles.size());  // sorted vertices, then the face index
    for (std::uint32_t i = 0; i < triangles.size(); ++i) {
      std::array<std::uint32_t, 4> key{triangles[i].vertex[0], triangles[i].vertex[1], triangles[i].vertex[2], i};
      std::sort(key.begin(), key.begin() + 3);
      keys[i] = key;
    }
    std::sort(keys.begin(), keys.end());
    std::size_t repeats = 0;
    std::uint32_t firstRepeat = 0;
    for (std::size_t k = 1; k < keys.size(); ++k)
      if (std::equal(keys[k].begin(), keys[k].begin() + 3, keys[k - 1].begin())) {
        if (repeats == 0 || keys[k][3] < firstRepeat) firstRepeat = keys[k][3];
        ++repeats;
      }
    if (repeats == 0) return;
    const PendingMesh& mesh = meshes_[triangles[firstRepeat].mesh];
    warn(mesh.line, plural(repeats, "face repeats", "faces repeat") +
                        " the three vertices of an earlier face (the first in " + meshName(mesh) +
                        "): coincident surfaces, where rayview shows the face listed first");
  }

  bool isDegenerate(const Triangle& t) const {
    if (t.vertex[0] == t.vertex[1] || t.vertex[1] == t.vertex[2] || t.vertex[0] == t.vertex[2]) return true;
    const auto& v = result_.scene.vertices;
    const glm::dvec3 n = glm::cross(v[t.vertex[1]] - v[t.vertex[0]], v[t.vertex[2]] - v[t.vertex[0]]);
    if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z)) return true;
    return n.x == 0.0 && n.y == 0.0 && n.z == 0.0;
  }

  // Finds the line of the corner-th index token of the mesh's <faces> (only on this error path).
  [[noreturn]] void indexOutOfRange(const PendingMesh& mesh, std::size_t corner, const char* kind, std::int64_t raw,
                                    std::int64_t base, std::int64_t count) {
    int line = mesh.faces->GetLineNum();
    std::size_t seen = 0;
    for (const Piece& piece : textOf(mesh.faces)) {
      detail::TokenScanner scanner(piece.text);
      for (std::string_view token = scanner.nextToken(); !token.empty(); token = scanner.nextToken())
        if (seen++ == corner) {
          line = lineIn(piece, token.data());
          goto found;
        }
    }
  found:
    const char* data = kind[0] == 'v' ? "vertices" : (kind[0] == 't' ? "<texturedata> coordinates" : "<normaldata> normals");
    std::string range = count == 0 ? std::string("the file has no ") + data
                                   : "the file has " + std::to_string(count) + " " + data + ", indices " +
                                         std::to_string(base) + ".." + std::to_string(count - 1 + base) +
                                         (base == 0 ? ", read as 0-based" : "");
    fail(line, meshName(mesh) + ": " + kind + " index " + std::to_string(raw) + " is out of range (" + range + ")");
  }

  void loadTexture() {
    Scene& scene = result_.scene;
    if (scene.textureImage.empty() || !options_.loadTexture) return;
    std::string tried;
    std::string lastReason;
    for (const fs::path& candidate : detail::textureCandidates(baseDirectory_, scene.textureImage)) {
      std::string reason;
      if (auto texture = detail::readTextureImage(candidate, reason)) {
        scene.texture = std::move(*texture);
        return;
      }
      if (reason != "not found") lastReason = candidate.string() + ": " + reason + "; ";
      tried += (tried.empty() ? "" : ", ") + candidate.string();
    }
    warn(textureImageLine_, "texture image \"" + scene.textureImage + "\" could not be read (" + lastReason +
                                "tried " + tried + "); rendering without the texture");
  }

  const std::string& file_;
  fs::path baseDirectory_;
  LoadOptions options_;
  LoadedScene result_;
  std::unordered_map<std::string, std::size_t> warningIndex_;
  std::vector<int> warningCounts_;

  bool haveDepth_ = false, haveBackground_ = false, haveAmbient_ = false;
  int cameraLine_ = 0;
  int textureImageLine_ = 0;
  std::unordered_map<std::string, int> materialLines_;
  std::unordered_map<std::string, std::uint32_t> materialIndex_;
  std::vector<PendingMesh> meshes_;
  IndexRange vertexRange_, textureRange_, normalRange_;
};

}  // namespace

LoadedScene loadSceneText(std::string_view xml, const std::string& displayName, const fs::path& baseDirectory,
                          const LoadOptions& options) {
  try {
    return Loader(displayName, baseDirectory, options).load(xml);
  } catch (const SceneError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throwSceneError({displayName, 0}, "out of memory while reading the scene");
  }
}

LoadedScene loadSceneFile(const fs::path& path, const LoadOptions& options) {
  const std::string display = path.string();
  std::error_code ec;
  if (fs::is_directory(path, ec)) throwSceneError({display, 0}, "cannot read the scene file: it is a directory");
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) throwSceneError({display, 0}, std::string("cannot open the scene file: ") + std::strerror(errno));
  std::string text;
  const std::uintmax_t size = fs::file_size(path, ec);
  if (!ec && size > kMaxFileBytes)
    throwSceneError({display, 0}, "the scene file is too large (" + std::to_string(size) + " bytes; the limit is 2 GiB)");
  if (!ec) text.reserve(static_cast<std::size_t>(size));
  char buffer[1 << 16];
  std::size_t got;
  while ((got = std::fread(buffer, 1, sizeof buffer, file.get())) > 0) {
    text.append(buffer, got);
    if (text.size() > kMaxFileBytes) throwSceneError({display, 0}, "the scene file is too large (the limit is 2 GiB)");
  }
  if (std::ferror(file.get())) throwSceneError({display, 0}, "cannot read the scene file");
  file.reset();
  fs::path directory = path.parent_path();
  LoadedScene loaded = loadSceneText(text, display, directory.empty() ? fs::path(".") : directory, options);
  loaded.scene.sourcePath = path;
  return loaded;
}

}  // namespace rayview
