#pragma once
// What the scene loader's files share (private to renderer/): the element names, the pieces of text and
// pending meshes the walk collects, and the Loader class whose members are defined in four files:
//   scene_loader_elements.cpp  tolerant element readers (messages, names, numbers, text)
//   scene_loader_walk.cpp      the element walk that fills Scene
//   scene_loader_checks.cpp    checks after the walk: materials, index base and ranges, the texture
//   scene_loader_stream.cpp    the big blocks read as a stream, before tinyxml2 sees the rest

#include "rayview/scene_loader.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <initializer_list>
#include <memory>
#include <string_view>
#include <unordered_map>

#include <glm/geometric.hpp>
#include <tinyxml2.h>

#include "number_list.h"
#include "rayview/accel.h"
#include "rayview/texture_image.h"
#include "xml_repair.h"

namespace rayview::scene_loading {

namespace fs = std::filesystem;
using detail::NumberStatus;
using tinyxml2::XMLElement;
using tinyxml2::XMLNode;

// --- limits (SPEC section 2: refuse up front what cannot fit) ---
constexpr std::int64_t kMaxRayDepthLimit = kMaxRayDepth;  // the depth's one limit (scene.h)
constexpr std::uintmax_t kMaxFileBytes = (1ULL << 31) - 1;  // tinyxml2 and line numbers use int
// What the files a scene reads are recorded as (rayview/input_files.h), for the messages refusing an output.
inline constexpr std::string_view kSceneFileRole = "the scene file";
inline constexpr std::string_view kTextureRole = "the scene's texture image";
inline constexpr std::string_view kMaterialTextureRole = "a material's texture image";

// --- element names ---
enum class Tag {
  Unknown, Scene, MaxRayTraceDepth, Background, ShadowRayEpsilon, Camera, Position, Gaze, Up, NearPlane,
  NearDistance, ImageResolution, Lights, AmbientLight,
  Light,  // the element of a light type (light_types.h); its own fields are read from the type's table
  Materials, Material, Ambient, Diffuse, Specular, PhongExponent, MirrorReflectance,
  TextureFactor, TwoSided, Emission, EmissionImage, BaseColor, MetallicRoughness, MetalRoughImage, AlphaImage, AlphaCutoff, ColorData, VertexData, TextureData, NormalData, TextureImage, Objects, Mesh, MaterialId, Faces,
  Count
};

struct TagName {
  std::string_view name;
  Tag tag;
};

inline constexpr TagName kTagNames[] = {
    {"scene", Tag::Scene}, {"maxraytracedepth", Tag::MaxRayTraceDepth}, {"background", Tag::Background},
    {"shadowrayepsilon", Tag::ShadowRayEpsilon}, {"camera", Tag::Camera}, {"position", Tag::Position},
    {"gaze", Tag::Gaze}, {"up", Tag::Up}, {"nearplane", Tag::NearPlane}, {"neardistance", Tag::NearDistance},
    {"imageresolution", Tag::ImageResolution}, {"lights", Tag::Lights}, {"ambientlight", Tag::AmbientLight},
    {"materials", Tag::Materials}, {"material", Tag::Material}, {"ambient", Tag::Ambient},
    {"diffuse", Tag::Diffuse}, {"specular", Tag::Specular}, {"phongexponent", Tag::PhongExponent},
    {"mirrorreflectance", Tag::MirrorReflectance}, {"texturefactor", Tag::TextureFactor},
    {"twosided", Tag::TwoSided}, {"emission", Tag::Emission}, {"emissionimage", Tag::EmissionImage},
    {"basecolor", Tag::BaseColor}, {"metallicroughness", Tag::MetallicRoughness},
    {"metallicroughnessimage", Tag::MetalRoughImage}, {"alphaimage", Tag::AlphaImage},
    {"alphacutoff", Tag::AlphaCutoff}, {"colordata", Tag::ColorData},
    {"vertexdata", Tag::VertexData}, {"texturedata", Tag::TextureData}, {"normaldata", Tag::NormalData},
    {"textureimage", Tag::TextureImage}, {"objects", Tag::Objects}, {"mesh", Tag::Mesh},
    {"materialid", Tag::MaterialId}, {"faces", Tag::Faces},
};

inline std::string toLower(std::string_view s) {
  std::string out(s);
  for (char& c : out)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return out;
}

inline std::string_view tagName(Tag tag) {
  for (const TagName& t : kTagNames)
    if (t.tag == tag) return t.name;
  return "?";
}

// A token as it appears in a message: quoted, shortened.
inline std::string quoted(std::string_view token) {
  constexpr std::size_t kMax = 32;
  std::string out = "'";
  out.append(token.substr(0, kMax));
  if (token.size() > kMax) out += "...";
  return out + "'";
}

// A token that should have been a number, quoted, and each character in it that cannot be part of one named
// with its column, since O and 0 or l and 1 look alike in many fonts: "'1OO' (letter O at column 2, letter O at
// column 3)". `allowed`: the characters a number of that kind may hold.
std::string quotedNumber(std::string_view token, std::string_view allowed = "0123456789.+-eE");

inline std::string plural(std::size_t n, const char* one, const char* many) {
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
  std::string label;  // how messages name it when not by id (the CENG477 dialect: <Triangle id="2">)
  bool fromPly = false;  // its faces index the PLY vertices (the CENG477 dialect's <Faces plyFile>)
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
  // As if every index `later` saw had been added here after this range's own.
  void merge(const IndexRange& later) {
    if (later.min == 0 && min != 0) firstZeroLine = later.firstZeroLine;
    min = std::min(min, later.min);
    max = std::max(max, later.max);
  }
};

// ---------------------------------------------------------------- the big blocks as a stream
// The text of every <vertexdata>, <texturedata>, <normaldata> and <faces> is parsed straight from the file a
// piece at a time (scene_loader_stream.cpp): tinyxml2 parses only the rest, the "skeleton", in which each
// block's text is a marker followed by the block's newlines (every line number stays the file's). The whole
// text is never held: at 1e7 triangles that was 105-150 bytes per triangle at the load's peak, and tinyxml2's
// scan of it most of the load's time. The stream reads only what it can read exactly as the DOM walk would:
// on anything else (a comment or child inside a block, a token that is not plainly a number or an index, an
// error anywhere) it gives up (StreamAbandoned) and the file is read the ordinary way, which then says what
// it says today. So the stream never has a message of its own, and every scene loads the same either way
// (tests/scene_stream_test.cpp, the fuzz target "scene").
struct StreamAbandoned {};

inline constexpr std::string_view kStreamMarker = "@stream:";

struct StreamedBlock {
  Tag tag = Tag::Unknown;
  std::uint64_t begin = 0, end = 0;  // the text's bytes in the file
  int line = 0;                      // the line of its first byte
  SceneArray<glm::dvec3> vertices;  // <vertexdata>
  std::vector<glm::vec2> texCoords;  // <texturedata>
  std::vector<glm::vec3> normals;    // <normaldata>
  std::uint32_t firstTriangle = 0, triangleCount = 0;  // <faces>: its range of StreamedBlocks::triangles
  IndexRange vertexRange, textureRange, normalRange;   // <faces>: as readFaces collects them
  bool claimed = false;                                // taken by the walk
};

// Reads `count` bytes at `offset` into `into`; returns how many (fewer only at the end), -1 on an error.
using ReadAt = std::function<long(std::uint64_t offset, char* into, std::size_t count)>;

struct StreamedBlocks {
  std::string skeleton;
  std::vector<StreamedBlock> blocks;  // in file order; the marker names the index
  SceneArray<Triangle> triangles;    // every <faces> block's, in file order, raw (file numbering)
  std::vector<FaceAttributes> faceAttributes;  // theirs, as SceneGeometry::faceAttributes (raw)
  std::uint64_t triangleCount = 0;
};

// The skeleton and where each block's text is (the first pass; the blocks are not parsed yet). Throws
// StreamAbandoned for what only the ordinary reading can report: a binary file, NUL bytes, a comment, CDATA or
// child element inside a block, the file ending inside one, a marker spelled out in the file.
// `size` is the file's, a hint for the buffer.
StreamedBlocks streamSkeleton(const ReadAt& read, std::uint64_t size);

// The loader's warnings and how often each was met: one owner for both, so a warning can only be added
// with its count (two separate owners once let repair messages reach the list but not the counts, and a
// repeated warning then wrote past the end of the counts). The same message again is counted, not listed.
class WarningList {
 public:
  void add(Diagnostic diagnostic);
  // The warnings sorted by line, each repeated one with "(N times; the first is shown)".
  std::vector<Diagnostic> take();

 private:
  struct Entry {
    Diagnostic diagnostic;
    std::size_t count = 1;
  };
  std::vector<Entry> entries_;
  std::unordered_map<std::string, std::size_t> index_;  // message -> entry
};

// Throws, naming what the file is, when `text` is binary or not UTF-8/ASCII (see file_read.h).
void refuseWhatIsNotText(const std::string& file, std::string_view text);

class Loader {
 public:
  Loader(const std::string& file, fs::path baseDirectory, const LoadOptions& options)
      : file_(file), baseDirectory_(std::move(baseDirectory)), options_(options) {}

  // `owned`, when given, is the string `text` views: it is released once tinyxml2 has parsed its own copy, so the
  // file's text is not held through the walk (at 1e6 triangles, ~100 MB less at the load's peak). With `source`,
  // the file `text` was read from, a text the repair pass leaves unchanged is released before parsing and
  // tinyxml2 reads the file itself: one copy of the text at the parse instead of two (the load's peak).
  LoadedScene load(std::string_view text, std::string* owned = nullptr, const fs::path* source = nullptr);

  // The second pass: each block's numbers, read again from `read` and parsed as the walk's readers would, on two
  // threads when `threads` allows and the file's faces and other blocks are both big. Throws StreamAbandoned where
  // they would report or warn.
  static void parseStreamedBlocks(StreamedBlocks& streamed, const ReadAt& read, int threads);

  // Loads from the skeleton, taking each block's numbers from `streamed`. Throws StreamAbandoned, or a
  // SceneError, when the ordinary reading must decide (the caller then makes it with a new Loader).
  LoadedScene loadStreamed(StreamedBlocks& streamed);

 private:
  // The walk from the parsed document to the scene: common to both readings.
  LoadedScene walk(const tinyxml2::XMLDocument& doc);

  // The block whose marker is `e`'s text, claimed (nullptr when `e` holds no marker).
  StreamedBlock* streamedBlock(const XMLElement* e, Tag tag);

  // ---------------------------------------------------------------- messages
  [[noreturn]] void fail(int line, const std::string& message) { throwSceneError({file_, line}, message); }

  // Warnings with the same text are reported once, at the first line, with a count.
  void warn(int line, const std::string& message);

  // Something the format does not allow but that we can read anyway: an error in strict mode.
  void nonconforming(int line, const std::string& message);

  // `text` is the file as read, for what an empty document really was.
  void xmlError(const tinyxml2::XMLDocument& doc, std::string_view text);

  // Built with append: GCC 12 warns (-Wrestrict, a false positive) on "<" + std::string(...).
  static std::string elementName(const XMLElement* e);

  // ---------------------------------------------------------------- names
  static bool isName(const XMLElement* e, std::string_view lowercase);

  // The element's name in lower case, with a misspelling read as the name it stands for (xml_repair.h).
  static std::string canonicalName(const XMLElement* e);

  // canonicalName, reporting the misspelling when there is one.
  std::string readName(const XMLElement* e);

  // The element's tag, after case folding and aliases (an alias is reported once per spelling).
  Tag identify(const XMLElement* e);

  // A name the format knows anywhere: a tag, a light type's element or one of its fields.
  static bool isKnownName(std::string_view canonical);
  // The known element name nearest `canonical` when it is a likely misspelling of one (at most 2 edits, letters
  // swapped counting as one), else "".
  static std::string nearestKnownName(std::string_view canonical);
  // Fails because `parent` lacks <missing>: at the line of a child that misspells it, with "did you mean", when
  // there is one; else at `line` with `message`.
  [[noreturn]] void failMissing(const XMLElement* parent, int line, std::string_view missing, const std::string& message);

  void unknownElement(const XMLElement* e, const std::string& where);

  void strayText(const tinyxml2::XMLText* text);

  // Calls `onElement(child, tag)` for each child element, warning about text and (through the callback
  // returning false) unexpected elements. Checks that single-valued children appear once.
  template <class F>
  void forEachChild(const XMLElement* parent, const std::string& where, F&& onElement) {
    int seen[static_cast<int>(Tag::Count)] = {};
    forEachElement(parent, [&](const XMLElement* child) {
      const Tag tag = identify(child);
      if (tag == Tag::Unknown) {
        unknownElement(child, where);
        return;
      }
      const bool repeatable = tag == Tag::Light || tag == Tag::Material ||
                              tag == Tag::Mesh || tag == Tag::Lights || tag == Tag::Materials || tag == Tag::Objects;
      int& first = seen[static_cast<int>(tag)];
      if (first != 0 && !repeatable)
        fail(child->GetLineNum(), "duplicate " + elementName(child) + " " + where + " (the first is at line " +
                                      std::to_string(first) + ")");
      if (first == 0) first = child->GetLineNum();
      if (!onElement(child, tag)) unknownElement(child, where);
    });
  }

  // The walk both dialects share: every child element in order, stray text warned about, comments skipped.
  template <typename F>
  void forEachElement(const XMLElement* parent, F&& onElement) {
    for (const XMLNode* node = parent->FirstChild(); node; node = node->NextSibling()) {
      if (const tinyxml2::XMLText* text = node->ToText()) {
        strayText(text);
        continue;
      }
      if (const XMLElement* child = node->ToElement()) onElement(child);  // else comments, declarations
    }
  }

  // ---------------------------------------------------------------- text and numbers
  std::vector<Piece> textOf(const XMLElement* e);

  static int lineIn(const Piece& piece, const char* p);

  // Hands every number of an element to `sink`, in order. `asFloat` also refuses values beyond float.
  void readNumbers(const XMLElement* e, bool asFloat, const std::function<void(double)>& sink);
  // The same, appended to `out`.
  void readNumbers(const XMLElement* e, std::vector<double>& out, bool asFloat);

  // Exactly `count` finite numbers.
  void readFixed(const XMLElement* e, std::size_t count, double* values, bool asFloat);

  glm::dvec3 readPoint(const XMLElement* e);
  Color readColor(const XMLElement* e);
  void readMetallicRoughness(const XMLElement* e, Material& material);
  void readAlphaCutoff(const XMLElement* e, Material& material);
  double readScalar(const XMLElement* e, bool asFloat);

  // Exactly `count` integers; `what` describes them for the message ("a non-negative integer").
  void readIntegers(const XMLElement* e, std::size_t count, std::int64_t* values, std::int64_t minimum,
                    const std::string& what);

  std::string attribute(const XMLElement* e, std::string_view name);
  bool hasAttribute(const XMLElement* e, std::string_view name);

  std::string trimmedText(const XMLElement* e);

  // ---------------------------------------------------------------- the METU CENG477 dialect
  // scene_loader_ceng477.cpp: the course's capitalised format, read into the same Scene as its conversion.
  static bool isCeng477(const XMLElement* root);

  // The dialect's loop over children: stray text warned, comments skipped; `onElement(child, lowercaseName)`
  // returns false for an element it does not know. A name in `once` may appear only once.
  template <class F>
  void forEachCeng477Child(const XMLElement* parent, std::initializer_list<std::string_view> once, F&& onElement) {
    std::vector<std::pair<std::string, int>> seen;
    forEachElement(parent, [&](const XMLElement* child) {
      const std::string name = toLower(child->Name());
      if (std::find(once.begin(), once.end(), name) != once.end()) {
        for (const auto& [earlier, line] : seen)
          if (earlier == name)
            fail(child->GetLineNum(), "duplicate " + elementName(child) + " inside " + elementName(parent) +
                                          " (the first is at line " + std::to_string(line) + ")");
        seen.emplace_back(name, child->GetLineNum());
      }
      if (!onElement(child, std::string_view(name))) unknownElement(child, "inside " + elementName(parent));
    });
  }

  void readCeng477Scene(const XMLElement* root);
  void readCeng477Cameras(const XMLElement* cameras);
  void readCeng477Camera(const XMLElement* camera);
  void readCeng477Lights(const XMLElement* lights);
  void readCeng477Materials(const XMLElement* materials);
  Material readCeng477Material(const XMLElement* e, bool typed);
  void readCeng477Objects(const XMLElement* objects);
  // <Mesh> and <Triangle>: false when the object is dropped (a child rayview cannot honour).
  bool readCeng477Object(const XMLElement* e, bool triangle);
  void readCeng477Triangle(const XMLElement* indices, PendingMesh& mesh);
  void readPlyFaces(PendingMesh& mesh, const std::string& plyFile);
  // After the walk: the PLY meshes' vertices join the scene's, after <VertexData>'s.
  void finishCeng477();
  // The course's parser keeps an element's first text only: text after a comment inside it is ignored.
  void keepFirstText(const XMLElement* e, std::vector<Piece>& pieces);

  // ---------------------------------------------------------------- the scene
  void readScene(const XMLElement* root);

  void readCamera(const XMLElement* cameraElement);
  // One of <camera>'s values by its tag (false for another tag), and the checks once all are read.
  bool readCameraField(const XMLElement* e, Tag tag);
  static unsigned cameraBit(Tag tag) { return 1u << (static_cast<unsigned>(tag) - static_cast<unsigned>(Tag::Position)); }
  void checkCamera(const tinyxml2::XMLElement* cameraElement, int line, unsigned have);
  void readMaxRayDepth(const XMLElement* e);
  void readShadowRayEpsilon(const XMLElement* e);

  static std::string trimmedNumber(double v);

  void readLights(const XMLElement* lights);

  // One light of type Light, its values read by the type's field table (light_type.h).
  template <class Light>
  void readLight(const XMLElement* e, std::vector<Light>& into);

  // <pointlight id="1"> as written, for messages.
  std::string describe(const XMLElement* e);

  void readMaterials(const XMLElement* materials);
  // A material's own image (its <textureimage>, <emissionimage>, <metallicroughnessimage> or <alphaimage>) into
  // `name`, remembered for loadTexture.
  void readMaterialTexture(const XMLElement* e, std::string& name);

  // ---------------------------------------------------------------- geometry
  // The numbers of a big block, `Stride` per item, each item handed to `item(const double*)` as soon as it is
  // read: no array of every number in between (at 1e7 triangles it held 12-72 B per triangle at the load's peak).
  // `reserve(n)` is told an estimate of the items first (detail::estimatedItems).
  template <std::size_t Stride, typename Reserve, typename Item>
  void readBlock(const XMLElement* e, const char* itemName, bool asFloat, Reserve&& reserve, Item&& item) {
    reserve(estimatedBlockItems(e, Stride));
    double values[Stride];
    std::size_t k = 0, count = 0;
    readNumbers(e, asFloat, [&](double v) {
      values[k++] = v;
      ++count;
      if (k == Stride) {
        item(values);
        k = 0;
      }
    });
    checkBlockCount(e, Stride, itemName, count);
  }
  // detail::estimatedItems for an element's text: its text nodes together, judged by the start of the first.
  static std::size_t estimatedBlockItems(const XMLElement* e, std::size_t tokensPerItem);
  void checkBlockCount(const XMLElement* e, std::size_t stride, const char* itemName, std::size_t count);

  void readVertices(const XMLElement* e);
  void readTexCoords(const XMLElement* e);
  void readNormals(const XMLElement* e);
  void readVertexColors(const XMLElement* e);

  void readObjects(const XMLElement* objects);

  std::string meshName(const PendingMesh& mesh) const;

  // Face tokens: v, v/t, v//n or v/t/n; stored raw (file numbering) until the index base is known.
  void readFaces(PendingMesh& mesh);

  static bool parseIndex(const char*& p, const char* end, std::int64_t& value);

  static bool parseCorner(std::string_view token, FaceCorner& corner);

  // ---------------------------------------------------------------- after the walk
  void finish(const XMLElement* root);

  std::string definedMaterials() const;

  // 1-based (the handout) unless the indices of a kind contain 0 and never reach the count (SPEC section 2).
  void resolveIndices(int rootLine);

  // Faces listed twice (same three vertices, any order or winding) are coincident surfaces: which one a
  // ray sees is a tie, which rayview gives to the face listed first. Real files do this (a wall written once
  // as a mirror and once as a colour), and the picture then depends on that rule: say so.
  void warnAboutDuplicatedFaces();

  bool isDegenerate(const Triangle& t) const;

  // Finds the line of the corner-th index token of the mesh's <faces> (only on this error path).
  [[noreturn]] void indexOutOfRange(const PendingMesh& mesh, std::size_t corner, const char* kind, std::int64_t raw,
                                    std::int64_t base, std::int64_t count);

  // The scene's texture and each image a material names, read relative to the file; one that cannot be read is a
  // warning at the line naming it, and the scene renders without it.
  void loadTexture();
  std::optional<Texture> readTextureNamed(const std::string& name, int line, std::string_view role);

  const std::string& file_;
  fs::path baseDirectory_;
  LoadOptions options_;
  LoadedScene result_;
  WarningList warnings_;

  bool haveDepth_ = false, haveBackground_ = false, haveAmbient_ = false;
  int cameraLine_ = 0;
  int textureImageLine_ = 0;
  int colorDataLine_ = 0;  // <colordata>, whose count the checks compare with the vertices'
  std::vector<std::pair<std::string, int>> materialTextureLines_;  // each name a material gives, first line
  std::unordered_map<std::string, int> materialLines_;
  std::unordered_map<std::string, std::uint32_t> materialIndex_;
  std::vector<PendingMesh> meshes_;
  IndexRange vertexRange_, textureRange_, normalRange_;
  bool ceng477_ = false;                 // the file is in the CENG477 dialect
  int firstDroppedObject_ = 0;           // the line of its first object rayview cannot render, and its name
  std::string firstDroppedName_;
  SceneArray<glm::dvec3> plyVertices_;  // the dialect's PLY meshes' vertices, in order, until finishCeng477
  StreamedBlocks* streamed_ = nullptr;  // when loading from a skeleton
  std::uint64_t claimedTriangles_ = 0;
  bool streamedTrianglesTaken_ = false;
};

}  // namespace rayview::scene_loading
