#include "rayview/scene_writer.h"

#include <cctype>
#include <charconv>
#include <system_error>

#include "rayview/image.h"
#include "rayview/scene_source.h"
#include "rayview/texture_image.h"

namespace rayview {
namespace {

namespace fs = std::filesystem;

std::string shortestDouble(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

double parseBack(const std::string& text) {
  double value = 0.0;
  std::from_chars(text.data(), text.data() + text.size(), value);
  return value;
}

std::string escapeXml(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// Appends numbers separated by single spaces.
class Line {
 public:
  explicit Line(std::string& out, NumberText style = NumberText::Shortest) : out_(out), style_(style) {}
  Line& operator<<(double v) {
    // A double that is exactly a float is written as the float's text (at most 9 digits) when asked.
    if (style_ == NumberText::FloatWhenExact && static_cast<double>(static_cast<float>(v)) == v)
      return put(formatNumber(static_cast<float>(v)));
    return put(formatNumber(v));
  }
  Line& operator<<(float v) { return put(formatNumber(v)); }
  Line& operator<<(int v) { return put(std::to_string(v)); }
  Line& operator<<(const glm::dvec3& v) { return *this << v.x << v.y << v.z; }
  Line& operator<<(const glm::vec3& v) { return *this << v.x << v.y << v.z; }
  Line& operator<<(const glm::vec2& v) { return *this << v.x << v.y; }

 private:
  Line& put(const std::string& text) {
    if (!first_) out_ += ' ';
    out_ += text;
    first_ = false;
    return *this;
  }
  std::string& out_;
  NumberText style_;
  bool first_ = true;
};

class XmlWriter {
 public:
  XmlWriter(std::string& out, NumberText style) : out_(out), style_(style) {}

  template <typename... Values>
  void element(int depth, std::string_view name, const Values&... values) {
    indent(depth);
    out_ += '<';
    out_ += name;
    out_ += '>';
    Line line(out_, style_);
    (line << ... << values);
    out_ += "</";
    out_ += name;
    out_ += ">\n";
  }
  void text(int depth, std::string_view name, const std::string& value) {
    indent(depth);
    out_.append("<").append(name).append(">").append(escapeXml(value)).append("</").append(name).append(">\n");
  }
  void open(int depth, std::string_view name, const std::string& id = {}, bool hasId = false) {
    indent(depth);
    out_.append("<").append(name);
    if (hasId) out_ += " id=\"" + escapeXml(id) + "\"";
    out_ += ">\n";
  }
  void close(int depth, std::string_view name) {
    indent(depth);
    out_.append("</").append(name).append(">\n");
  }
  void indent(int depth) { out_.append(static_cast<std::size_t>(depth) * 4, ' '); }
  std::string& raw() { return out_; }
  NumberText style() const { return style_; }

 private:
  std::string& out_;
  NumberText style_;
};

void appendIndex(std::string& out, std::int64_t zeroBased) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, zeroBased + 1);  // the handout is 1-based
  out.append(buffer, result.ptr);
}

void writeFace(std::string& out, const Triangle& t, const FaceAttributes& a) {
  for (int k = 0; k < 3; ++k) {
    if (k) out += ' ';
    appendIndex(out, t.vertex[k]);
    if (a.texCoord[k] == kNoIndex && a.normal[k] == kNoIndex) continue;
    out += '/';
    if (a.texCoord[k] != kNoIndex) appendIndex(out, a.texCoord[k]);
    if (a.normal[k] != kNoIndex) {
      out += '/';
      appendIndex(out, a.normal[k]);
    }
  }
}

bool sameFile(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  const bool same = fs::equivalent(a, b, ec);
  return !ec && same;
}

}  // namespace

std::string formatNumber(double value) { return shortestDouble(value); }

std::string formatNumber(float value) {
  // The loader reads a double and narrows it. The float's own shortest text almost always survives that
  // double rounding; when it would not, the double's text of the float's exact value always does.
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  std::string text(buffer, result.ptr);
  if (static_cast<float>(parseBack(text)) == value) return text;
  return shortestDouble(static_cast<double>(value));
}

std::string sceneToXml(const Scene& scene, const std::string& textureImage) {
  return sceneToXml(scene.parameters(), scene.geometry(), textureImage);
}

namespace {

// The camera, the lights and the materials.
void writeParameters(XmlWriter& xml, const SceneParameters& parameters) {
  const Camera& c = parameters.camera;
  xml.open(1, "camera");
  xml.element(2, "position", c.position);
  xml.element(2, "gaze", c.gaze);
  xml.element(2, "up", c.up);
  xml.element(2, "nearplane", c.left, c.right, c.bottom, c.top);
  xml.element(2, "neardistance", c.nearDistance);
  xml.element(2, "imageresolution", c.width, c.height);
  xml.close(1, "camera");

  xml.open(1, "lights");
  xml.element(2, "ambientlight", parameters.ambientLight);
  parameters.lights.forEachType([&](const auto& list) {
    using Light = LightOf<decltype(list)>;
    for (const Light& light : list) {
      xml.open(2, Light::kType.element, light.id, true);
      for (const auto& field : Light::fields()) {
        if (field.point) xml.element(3, field.element, light.*field.point);
        else xml.element(3, field.element, light.*field.intensity);
      }
      xml.close(2, Light::kType.element);
    }
  });
  xml.close(1, "lights");

  xml.open(1, "materials");
  for (const Material& m : parameters.materials) {
    xml.open(2, "material", m.id, true);
    xml.element(3, "ambient", m.ambient);
    xml.element(3, "diffuse", m.diffuse);
    xml.element(3, "specular", m.specular);
    xml.element(3, "phongexponent", m.phongExponent);
    xml.element(3, "mirrorreflectance", m.mirror);
    // A 2025 element: written only when it matters, so 2024 scenes stay 2024 files.
    if (m.textureFactor != 0.0f) xml.element(3, "texturefactor", m.textureFactor);
    if (m.twoSided) xml.element(3, "twosided", 1);
    if (!m.textureImage.empty()) xml.text(3, "textureimage", m.textureImage);
    if (m.emits()) xml.element(3, "emission", m.emission);
    if (!m.emissionImage.empty()) xml.text(3, "emissionimage", m.emissionImage);
    if (!m.metalRoughImage.empty()) {
      xml.element(3, "basecolor", m.baseColor);
      xml.element(3, "metallicroughness", m.metallic, m.roughness);
      xml.text(3, "metallicroughnessimage", m.metalRoughImage);
    }
    if (!m.alphaImage.empty()) {
      xml.text(3, "alphaimage", m.alphaImage);
      xml.element(3, "alphacutoff", m.alphaCutoff);
    }
    xml.close(2, "material");
  }
  xml.close(1, "materials");
}

}  // namespace

std::string sceneToXml(const SceneParameters& parameters, const SceneGeometry& geometry,
                       const std::string& textureImage, NumberText style) {
  std::string out;
  // Faces dominate the size of big scenes: about 3 indices of up to 8 digits per triangle.
  out.reserve(4096 + geometry.vertices.size() * 64 + geometry.triangles.size() * 40 +
              (geometry.texCoords.size() + geometry.normals.size()) * 48);
  XmlWriter xml(out, style);
  out += "<!-- written by rayview " RAYVIEW_VERSION " -->\n";
  xml.open(0, "scene");
  xml.element(1, "maxraytracedepth", parameters.maxRayDepth);
  xml.element(1, "background", parameters.background);
  if (parameters.shadowRayEpsilon) xml.element(1, "shadowrayepsilon", *parameters.shadowRayEpsilon);

  writeParameters(xml, parameters);

  xml.open(1, "vertexdata");
  for (const glm::dvec3& v : geometry.vertices) {
    xml.indent(2);
    Line(out, style) << v;
    out += '\n';
  }
  xml.close(1, "vertexdata");
  if (!geometry.texCoords.empty()) {
    xml.open(1, "texturedata");
    for (const glm::vec2& t : geometry.texCoords) {
      xml.indent(2);
      Line(out) << t;
      out += '\n';
    }
    xml.close(1, "texturedata");
  }
  if (!geometry.normals.empty()) {
    xml.open(1, "normaldata");
    for (const glm::vec3& n : geometry.normals) {
      xml.indent(2);
      Line(out) << n;
      out += '\n';
    }
    xml.close(1, "normaldata");
  }
  if (!geometry.vertexColors.empty()) {
    xml.open(1, "colordata");
    for (const Color& c : geometry.vertexColors) {
      xml.indent(2);
      Line(out) << c;
      out += '\n';
    }
    xml.close(1, "colordata");
  }
  if (!textureImage.empty()) xml.text(1, "textureimage", textureImage);

  xml.open(1, "objects");
  for (const Mesh& mesh : geometry.meshes) {
    xml.open(2, "mesh", mesh.id, true);
    xml.text(3, "materialid", mesh.material < parameters.materials.size() ? parameters.materials[mesh.material].id : "");
    xml.open(3, "faces");
    const std::size_t end = geometry.meshEnd(mesh);
    for (std::size_t i = mesh.firstTriangle; i < end; ++i) {
      xml.indent(4);
      writeFace(out, geometry.triangles[i], geometry.attributesOf(i));
      out += '\n';
    }
    xml.close(3, "faces");
    xml.close(2, "mesh");
  }
  xml.close(1, "objects");
  xml.close(0, "scene");
  return out;
}

std::string textureReferenceFor(const Scene& scene, const std::string& name, const fs::path& outputPath) {
  // Only the name and the file the scene came from matter here.
  if (name.empty()) return {};
  const fs::path sourceDirectory = scene.sourcePath.parent_path();
  const fs::path outputDirectory = outputPath.parent_path().empty() ? fs::path(".") : outputPath.parent_path();
  if (sameFile(sourceDirectory.empty() ? fs::path(".") : sourceDirectory, outputDirectory)) return name;
  std::error_code ec;
  for (const fs::path& candidate : detail::textureCandidates(sourceDirectory, name)) {
    if (!fs::is_regular_file(candidate, ec)) continue;
    const fs::path found = fs::weakly_canonical(fs::absolute(candidate, ec), ec);
    // Relative when the two directories share a root, so the pair can be moved together.
    const fs::path relative = fs::relative(found, fs::weakly_canonical(fs::absolute(outputDirectory, ec), ec), ec);
    if (!ec && !relative.empty()) return relative.generic_string();
    return found.generic_string();
  }
  return name;  // never found: keep what the author wrote (it stays a warning on load)
}

std::string textureReferenceFor(const Scene& scene, const fs::path& outputPath) {
  return textureReferenceFor(scene, scene.textureImage, outputPath);
}

void writeSceneFile(const fs::path& outputPath, const SceneParameters& parameters, const Scene& loaded) {
  // A scene is XML: a name that says image (or anything else) would make a file no viewer of that kind opens.
  std::string extension = outputPath.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (extension != ".xml")
    throw ImageIoError("cannot write " + outputPath.string() + ": a scene is saved as .xml, not " +
                       (extension.empty() ? std::string("a name without an extension") : "'" + extension + "'"));
  if (const std::string problem = outputOverwritesInput(outputPath, loaded.sourcePath.string(), &loaded); !problem.empty())
    throw ImageIoError(problem);
  // The materials' own textures are found as the scene's is, from the file the scene came from.
  SceneParameters written = parameters;
  for (Material& m : written.materials)
    for (std::string* name : m.images()) *name = textureReferenceFor(loaded, *name, outputPath);
  writeFileAtomically(outputPath, sceneToXml(written, loaded.geometry(), textureReferenceFor(loaded, outputPath)));
}

void writeSceneFile(const fs::path& outputPath, const Scene& scene) {
  writeSceneFile(outputPath, scene.parameters(), scene);
}

}  // namespace rayview
