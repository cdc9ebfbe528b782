// The scene loader's element walk: <scene> and its children into Scene, faces kept in file numbering
// until the checks after the walk (scene_loader_checks.cpp) know the index base.

#include "rayview/image_limits.h"
#include "scene_loader_internal.h"

namespace rayview::scene_loading {

void Loader::readScene(const XMLElement* root) {
  Scene& scene = result_.scene;
  forEachChild(root, "inside <scene>", [&](const XMLElement* e, Tag tag) {
    switch (tag) {
      case Tag::MaxRayTraceDepth: readMaxRayDepth(e); return true;
      case Tag::Background:
        scene.background = readColor(e);
        haveBackground_ = true;
        return true;
      case Tag::ShadowRayEpsilon: readShadowRayEpsilon(e); return true;
      case Tag::Camera: readCamera(e); return true;
      case Tag::Lights: readLights(e); return true;
      case Tag::Materials: readMaterials(e); return true;
      case Tag::VertexData: readVertices(e); return true;
      case Tag::TextureData: readTexCoords(e); return true;
      case Tag::NormalData: readNormals(e); return true;
      case Tag::ColorData: readVertexColors(e); return true;
      case Tag::TextureImage:
        scene.textureImage = trimmedText(e);
        textureImageLine_ = e->GetLineNum();
        return true;
      case Tag::Objects: readObjects(e); return true;
      default: return false;
    }
  });
}

void Loader::readMaxRayDepth(const XMLElement* e) {
  std::int64_t depth = 0;
  readIntegers(e, 1, &depth, 0, "a non-negative integer");
  if (depth > kMaxRayDepthLimit)
    fail(e->GetLineNum(), elementName(e) + ": " + std::to_string(depth) + " is above the limit of " +
                              std::to_string(kMaxRayDepthLimit));
  result_.scene.maxRayDepth = static_cast<int>(depth);
  haveDepth_ = true;
}

void Loader::readShadowRayEpsilon(const XMLElement* e) {
  double epsilon = readScalar(e, false);
  if (epsilon < 0.0) fail(e->GetLineNum(), elementName(e) + ": must be >= 0, found " + trimmedText(e));
  // Larger than any distance rayview traces (Embree's coordinates stop at kEmbreeCoordinateLimit):
  // such an epsilon is a typo, and would push every shadow ray out of range.
  if (epsilon > kEmbreeCoordinateLimit)
    fail(e->GetLineNum(), elementName(e) + ": " + trimmedText(e) + " is larger than any distance rayview can trace "
                          "(the limit is 1e18)");
  result_.scene.shadowRayEpsilon = epsilon;
}

void Loader::readCamera(const XMLElement* cameraElement) {
  const int line = cameraElement->GetLineNum();
  cameraLine_ = line;
  unsigned have = 0;
  forEachChild(cameraElement, "inside <camera>", [&](const XMLElement* e, Tag tag) {
    if (!readCameraField(e, tag)) return false;
    have |= cameraBit(tag);
    return true;
  });
  checkCamera(cameraElement, line, have);
}

bool Loader::readCameraField(const XMLElement* e, Tag tag) {
  Camera& camera = result_.scene.camera;
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
      // More than any buffer of that size can hold, at the element's own line (not positive: the camera's check).
      if (const std::string problem = imageSizeProblem(v[0], v[1]); v[0] > 0 && v[1] > 0 && !problem.empty())
        fail(e->GetLineNum(), elementName(e) + ": " + problem);
      camera.width = static_cast<int>(std::clamp<std::int64_t>(v[0], INT32_MIN, INT32_MAX));
      camera.height = static_cast<int>(std::clamp<std::int64_t>(v[1], INT32_MIN, INT32_MAX));
      break;
    }
    default: return false;
  }
  return true;
}

void Loader::checkCamera(const XMLElement* cameraElement, int line, unsigned have) {
  const Camera& camera = result_.scene.camera;
  constexpr Tag kFields[] = {Tag::Position, Tag::Gaze, Tag::Up, Tag::NearPlane, Tag::NearDistance, Tag::ImageResolution};
  constexpr const char* kCeng477Names[] = {"Position", "Gaze", "Up", "NearPlane", "NearDistance", "ImageResolution"};
  for (std::size_t i = 0; i < std::size(kFields); ++i)
    if (!(have & cameraBit(kFields[i]))) {
      if (ceng477_) fail(line, "<Camera> has no <" + std::string(kCeng477Names[i]) + ">");
      failMissing(cameraElement, line, tagName(kFields[i]), "<camera> has no <" + std::string(tagName(kFields[i])) + ">");
    }

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

void Loader::readLights(const XMLElement* lights) {
  Scene& scene = result_.scene;
  forEachChild(lights, "inside <lights>", [&](const XMLElement* e, Tag tag) {
    switch (tag) {
      case Tag::AmbientLight:
        scene.ambientLight = readColor(e);
        haveAmbient_ = true;
        return true;
      case Tag::Light: {
        const std::string name = canonicalName(e);
        scene.lights.forEachType([&](auto& list) {
          if (LightOf<decltype(list)>::kType.element == name) readLight(e, list);
        });
        return true;
      }
      default: return false;
    }
  });
}

template <class Light>
void Loader::readLight(const XMLElement* e, std::vector<Light>& into) {
  Light light;
  light.id = attribute(e, "id");
  constexpr auto fields = Light::fields();
  int firstLine[fields.size()] = {};  // of each field's element, 0 until met
  const std::string where = "inside " + elementName(e);
  for (const XMLNode* node = e->FirstChild(); node; node = node->NextSibling()) {
    if (const tinyxml2::XMLText* text = node->ToText()) {
      strayText(text);
      continue;
    }
    const XMLElement* child = node->ToElement();
    if (!child) continue;  // comments
    const std::string name = readName(child);
    std::size_t i = 0;
    while (i < fields.size() && fields[i].element != name) ++i;
    if (i == fields.size()) {
      unknownElement(child, where);
      continue;
    }
    if (firstLine[i] != 0)
      fail(child->GetLineNum(), "duplicate " + elementName(child) + " " + where + " (the first is at line " +
                                    std::to_string(firstLine[i]) + ")");
    firstLine[i] = child->GetLineNum();
    if (fields[i].point) light.*fields[i].point = readPoint(child);
    else light.*fields[i].intensity = readColor(child);
  }
  for (std::size_t i = 0; i < fields.size(); ++i)
    if (firstLine[i] == 0)
      failMissing(e, e->GetLineNum(), fields[i].element, describe(e) + " has no <" + std::string(fields[i].element) + ">");
  into.push_back(std::move(light));
}

// The CENG477 dialect (scene_loader_ceng477.cpp) reads its <PointLight> with the same field table.
template void Loader::readLight<PointLight>(const XMLElement* e, std::vector<PointLight>& into);

void Loader::readMaterials(const XMLElement* materials) {
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
        case Tag::TextureImage: readMaterialTexture(c, material.textureImage); break;
        case Tag::Emission: material.emission = readColor(c); break;
        case Tag::EmissionImage: readMaterialTexture(c, material.emissionImage); break;
        case Tag::BaseColor: material.baseColor = readColor(c); break;
        case Tag::MetallicRoughness: readMetallicRoughness(c, material); break;
        case Tag::MetalRoughImage: readMaterialTexture(c, material.metalRoughImage); break;
        case Tag::AlphaImage: readMaterialTexture(c, material.alphaImage); break;
        case Tag::AlphaCutoff: readAlphaCutoff(c, material); break;
        case Tag::TwoSided: {
          std::int64_t flag = 0;
          readIntegers(c, 1, &flag, 0, "0 or 1");
          if (flag > 1) fail(c->GetLineNum(), elementName(c) + ": expected 0 or 1, found " + trimmedText(c));
          material.twoSided = flag == 1;
          break;
        }
        default: return false;
      }
      return true;
    });
    const char* names[] = {"ambient", "diffuse", "specular", "phongexponent"};
    for (int i = 0; i < 4; ++i)
      if (!(have & (1u << i)))
        failMissing(e, e->GetLineNum(), names[i], describe(e) + " has no <" + std::string(names[i]) + ">");
    if (!(have & 16))
      warn(e->GetLineNum(), describe(e) + " has no <mirrorreflectance>; using 0 0 0 (not a mirror)");
    materialIndex_.emplace(material.id, static_cast<std::uint32_t>(scene.materials.size()));
    scene.materials.push_back(std::move(material));
    return true;
  });
}

void Loader::readMaterialTexture(const XMLElement* e, std::string& name) {
  name = trimmedText(e);
  if (name.empty()) return;  // as at the scene's level: no name, no image of its own
  const auto named = [&](const auto& entry) { return entry.first == name; };
  if (std::none_of(materialTextureLines_.begin(), materialTextureLines_.end(), named))
    materialTextureLines_.emplace_back(name, e->GetLineNum());
}

std::size_t Loader::estimatedBlockItems(const XMLElement* e, std::size_t tokensPerItem) {
  std::size_t textSize = 0;
  std::string_view sample;
  for (const XMLNode* node = e->FirstChild(); node; node = node->NextSibling()) {
    if (!node->ToText()) continue;
    const std::string_view text = node->Value();
    if (sample.empty()) sample = text.substr(0, detail::kEstimateSample);
    textSize += text.size();
  }
  return detail::estimatedItems(sample, textSize, tokensPerItem);
}

void Loader::checkBlockCount(const XMLElement* e, std::size_t stride, const char* itemName, std::size_t count) {
  if (count % stride != 0)
    fail(e->GetLineNum(), elementName(e) + ": expected " + std::to_string(stride) + " numbers per " + itemName +
                              ", found " + std::to_string(count) + " numbers (not a multiple of " +
                              std::to_string(stride) + ")");
  if (count / stride > static_cast<std::size_t>(INT32_MAX))
    fail(e->GetLineNum(), elementName(e) + ": too many " + itemName + "s");
}

void Loader::readVertices(const XMLElement* e) {
  auto& vertices = result_.scene.vertices;
  if (StreamedBlock* block = streamedBlock(e, Tag::VertexData)) {
    vertices = std::move(block->vertices);
    return;
  }
  vertices.clear();
  readBlock<3>(
      e, "vertex", false, [&](std::size_t n) { vertices.reserve(n); },
      [&](const double* v) { vertices.emplace_back(v[0], v[1], v[2]); });
}

void Loader::readTexCoords(const XMLElement* e) {
  auto& uvs = result_.scene.texCoords;
  if (StreamedBlock* block = streamedBlock(e, Tag::TextureData)) {
    uvs = std::move(block->texCoords);
    return;
  }
  uvs.clear();
  readBlock<2>(
      e, "texture coordinate", true, [&](std::size_t n) { uvs.reserve(n); },
      [&](const double* v) { uvs.emplace_back(static_cast<float>(v[0]), static_cast<float>(v[1])); });
}

void Loader::readNormals(const XMLElement* e) {
  auto& normals = result_.scene.normals;
  if (StreamedBlock* block = streamedBlock(e, Tag::NormalData)) {
    normals = std::move(block->normals);
    return;
  }
  normals.clear();
  readBlock<3>(
      e, "normal", true, [&](std::size_t n) { normals.reserve(n); },
      [&](const double* v) {
        normals.emplace_back(static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]));
      });
}

void Loader::readVertexColors(const XMLElement* e) {
  auto& colors = result_.scene.vertexColors;
  colors.clear();
  colorDataLine_ = e->GetLineNum();
  readBlock<3>(
      e, "vertex colour", true, [&](std::size_t n) { colors.reserve(n); },
      [&](const double* v) {
        colors.emplace_back(static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]));
      });
}

void Loader::readObjects(const XMLElement* objects) {
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
    if (!haveMaterial) failMissing(e, mesh.line, "materialid", describe(e) + " has no <materialid>");
    if (!mesh.faces) failMissing(e, mesh.line, "faces", describe(e) + " has no <faces>");
    readFaces(mesh);
    meshes_.push_back(std::move(mesh));
    return true;
  });
}

std::string Loader::meshName(const PendingMesh& mesh) const {
  return mesh.label.empty() ? "mesh \"" + mesh.id + "\"" : mesh.label;
}

// Face tokens: v, v/t, v//n or v/t/n; stored raw (file numbering) until the index base is known.
void Loader::readFaces(PendingMesh& mesh) {
  const XMLElement* e = mesh.faces;
  SceneArray<Triangle>& triangles = result_.scene.triangles;
  if (StreamedBlock* block = streamedBlock(e, Tag::Faces)) {
    // The stream's faces, in file order: the first block brings them all, each mesh takes its range in turn.
    if (block->firstTriangle != claimedTriangles_) throw StreamAbandoned{};
    if (!streamedTrianglesTaken_) {
      if (!triangles.empty()) throw StreamAbandoned{};
      triangles.swap(streamed_->triangles);
      result_.scene.faceAttributes.swap(streamed_->faceAttributes);
      streamedTrianglesTaken_ = true;
    }
    claimedTriangles_ += block->triangleCount;
    mesh.firstTriangle = block->firstTriangle;
    mesh.triangleCount = block->triangleCount;
    vertexRange_.merge(block->vertexRange);
    textureRange_.merge(block->textureRange);
    normalRange_.merge(block->normalRange);
    return;
  }
  if (triangles.size() > static_cast<std::size_t>(UINT32_MAX / 2))
    fail(e->GetLineNum(), "too many triangles");
  mesh.firstTriangle = static_cast<std::uint32_t>(triangles.size());
  const std::vector<Piece> pieces = textOf(e);
  std::size_t textSize = 0;
  for (const Piece& piece : pieces) textSize += piece.text.size();
  const std::string_view sample =
      pieces.empty() ? std::string_view() : pieces.front().text.substr(0, detail::kEstimateSample);
  // At least doubling when it grows: a scene of many small meshes must not copy its triangles once per mesh.
  const std::size_t wanted = triangles.size() + detail::estimatedItems(sample, textSize, 3);
  if (wanted > triangles.capacity()) triangles.reserve(std::max(wanted, 2 * triangles.size()));

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
                       quotedNumber(token, "0123456789/+-"));
      }
      ++indexCount;
      if (++cornerCount < 3) continue;
      cornerCount = 0;
      if ((corners[0].t < 0) != (corners[1].t < 0) || (corners[0].t < 0) != (corners[2].t < 0) ||
          (corners[0].n < 0) != (corners[1].n < 0) || (corners[0].n < 0) != (corners[2].n < 0))
        fail(lineIn(piece, token.data()), meshName(mesh) + ": a face mixes index forms (v, v/t, v//n, v/t/n) in " +
                                              "its three corners; the last one is " + quoted(token));
      Triangle triangle;
      FaceAttributes attributes;
      for (int k = 0; k < 3; ++k) {
        triangle.vertex[k] = static_cast<std::uint32_t>(corners[k].v);
        attributes.texCoord[k] = static_cast<std::int32_t>(corners[k].t);
        attributes.normal[k] = static_cast<std::int32_t>(corners[k].n);
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
      result_.scene.addFace(triangle, attributes);
    }
  }
  if (cornerCount != 0)
    fail(e->GetLineNum(), meshName(mesh) + ": " + elementName(e) + " has " + std::to_string(indexCount) +
                              " vertex indices, not a multiple of 3");
  mesh.triangleCount = static_cast<std::uint32_t>(triangles.size() - mesh.firstTriangle);
}

bool Loader::parseIndex(const char*& p, const char* end, std::int64_t& value) {
  auto [ptr, ec] = std::from_chars(p, end, value);
  if (ptr == p || ec != std::errc() || value < 0 || value > INT32_MAX) return false;
  p = ptr;
  return true;
}

bool Loader::parseCorner(std::string_view token, FaceCorner& corner) {
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

}  // namespace rayview::scene_loading
