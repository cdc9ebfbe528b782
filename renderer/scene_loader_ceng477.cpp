// The METU CENG477 dialect of the loader: the course's capitalised scene files (<Scene>, <Cameras>,
// <MaxRecursionDepth>, <Material>N</Material>, <Triangle>, <Faces plyFile>), read into the Scene their conversion by
// shared/tools/ceng477_to_cse461.py gives, following the course's own parser where the formats differ
// (docs/scene-format.md, "The CENG477 dialect"). The element readers, the big blocks (also as a stream) and the
// checks after the walk are the handout format's.

#include <cmath>
#include <filesystem>

#include "rayview/ply_reader.h"
#include "scene_loader_internal.h"

namespace rayview::scene_loading {

namespace {

// The course parser's default when a file has no <ShadowRayEpsilon> (shared/conformance/ceng477/SOURCES.md).
constexpr double kCourseShadowRayEpsilon = 1e-3;

bool isWhole(float v) { return v == std::floor(v); }  // finite: readColor refuses the rest

}  // namespace

bool Loader::isCeng477(const XMLElement* root) {
  if (!isName(root, "scene")) return false;
  for (const XMLElement* child = root->FirstChildElement(); child; child = child->NextSiblingElement())
    if (isName(child, "cameras")) return true;
  return false;
}

void Loader::keepFirstText(const XMLElement* e, std::vector<Piece>& pieces) {
  if (pieces.empty()) return;
  if (!e->FirstChild()->ToText())
    fail(pieces.front().line, elementName(e) + ": the value comes after a comment or an element; the CENG477 format's "
                              "value is an element's first text, and this element has none before it");
  for (std::size_t i = 1; i < pieces.size(); ++i) {
    const std::string_view text = pieces[i].text;
    if (std::all_of(text.begin(), text.end(), detail::isXmlSpace)) continue;
    nonconforming(pieces[i].line, elementName(e) + ": text after a comment is ignored (the CENG477 format's value "
                                  "is an element's first text, as the course's parser reads it)");
    break;
  }
  pieces.resize(1);
}

void Loader::readCeng477Scene(const XMLElement* root) {
  Scene& scene = result_.scene;
  scene.shadowRayEpsilon = kCourseShadowRayEpsilon;
  forEachCeng477Child(root,
                      {"backgroundcolor", "shadowrayepsilon", "intersectiontestepsilon", "maxrecursiondepth", "cameras",
                       "lights", "materials", "vertexdata", "objects"},
                      [&](const XMLElement* e, std::string_view name) {
    if (name == "backgroundcolor") {
      scene.background = readColor(e);
      haveBackground_ = true;
      const Color& c = scene.background;
      if (!isWhole(c.x) || !isWhole(c.y) || !isWhole(c.z))
        warn(e->GetLineNum(), "<BackgroundColor> " + trimmedText(e) + " is read as written; the course's parser "
                              "reads whole numbers only");
    } else if (name == "shadowrayepsilon") {
      readShadowRayEpsilon(e);
    } else if (name == "intersectiontestepsilon") {
      // Checked, not used: rayview's triangle test is watertight and needs no tolerance.
      if (readScalar(e, false) < 0.0) fail(e->GetLineNum(), elementName(e) + ": must be >= 0, found " + trimmedText(e));
    } else if (name == "maxrecursiondepth") {
      readMaxRayDepth(e);
    } else if (name == "cameras") {
      readCeng477Cameras(e);
    } else if (name == "lights") {
      readCeng477Lights(e);
    } else if (name == "materials") {
      readCeng477Materials(e);
    } else if (name == "vertexdata") {
      if (hasAttribute(e, "binaryFile"))
        fail(e->GetLineNum(), "<VertexData binaryFile=\"" + attribute(e, "binaryFile") + "\">: binary vertex files "
                              "are not supported (write the vertices as text)");
      readVertices(e);
    } else if (name == "objects") {
      readCeng477Objects(e);
    } else {
      return false;
    }
    return true;
  });
}

void Loader::readCeng477Cameras(const XMLElement* cameras) {
  std::vector<const XMLElement*> list;
  forEachCeng477Child(cameras, {}, [&](const XMLElement* e, std::string_view name) {
    if (name != "camera") return false;
    list.push_back(e);
    return true;
  });
  if (list.empty()) fail(cameras->GetLineNum(), "<Cameras> has no <Camera>");
  // Every camera's output name, whichever is read: a render into a directory writes each to its own, as the course's
  // renderer does.
  for (const XMLElement* camera : list) {
    std::string name;
    for (const XMLElement* c = camera->FirstChildElement(); c; c = c->NextSiblingElement())
      if (isName(c, "imagename")) name = trimmedText(c);
    result_.cameraImageNames.push_back(std::move(name));
  }
  const std::size_t wanted = options_.camera > 0 ? static_cast<std::size_t>(options_.camera) : 1;
  if (wanted > list.size())
    fail(cameras->GetLineNum(), "camera " + std::to_string(wanted) + " was asked for, but <Cameras> has " +
                                    plural(list.size(), "camera", "cameras"));
  const XMLElement* camera = list[wanted - 1];
  if (list.size() > 1 && options_.camera == 0)
    warn(camera->GetLineNum(), "<Cameras> has " + std::to_string(list.size()) +
                                   " cameras: rendering the first (choose another with --camera N)");
  readCeng477Camera(camera);
}

void Loader::readCeng477Camera(const XMLElement* e) {
  const int line = e->GetLineNum();
  if (const std::string type = attribute(e, "type"); !type.empty())
    fail(line, describe(e) + ": camera type \"" + type + "\" is not supported (rayview reads the camera of "
               "<Position> <Gaze> <Up> <NearPlane> <NearDistance> <ImageResolution>)");
  cameraLine_ = line;
  unsigned have = 0;
  forEachCeng477Child(e, {"position", "gaze", "up", "nearplane", "neardistance", "imageresolution", "imagename", "numsamples"},
                      [&](const XMLElement* c, std::string_view name) {
    if (name == "imagename") return true;  // the course's output file: rayview is told where to write
    if (name == "numsamples") {
      std::int64_t samples = 1;
      readIntegers(c, 1, &samples, 1, "a positive integer");
      if (samples > 1)
        warn(c->GetLineNum(), "<NumSamples>" + std::to_string(samples) + "</NumSamples>: rendered with one sample per "
                              "pixel (anti-aliasing is the --samples option)");
      return true;
    }
    Tag tag = Tag::Unknown;
    for (Tag t : {Tag::Position, Tag::Gaze, Tag::Up, Tag::NearPlane, Tag::NearDistance, Tag::ImageResolution})
      if (tagName(t) == name) tag = t;
    if (!readCameraField(c, tag)) return false;
    have |= cameraBit(tag);
    return true;
  });
  checkCamera(e, line, have);
}

void Loader::readCeng477Lights(const XMLElement* lights) {
  Scene& scene = result_.scene;
  forEachCeng477Child(lights, {"ambientlight"}, [&](const XMLElement* e, std::string_view name) {
    if (name == "ambientlight") {
      scene.ambientLight = readColor(e);
      haveAmbient_ = true;
    } else if (name == "pointlight") {
      std::vector<PointLight>& points = scene.lights.of<PointLight>();
      readLight(e, points);
      if (points.back().id.empty()) points.back().id = std::to_string(points.size());
    } else if (name.size() > 5 && name.substr(name.size() - 5) == "light") {
      nonconforming(e->GetLineNum(), elementName(e) + " is a CENG477 light rayview does not render (point and ambient "
                                     "lights only): ignored, the image lacks its light");
    } else {
      return false;
    }
    return true;
  });
}

void Loader::readCeng477Materials(const XMLElement* materials) {
  Scene& scene = result_.scene;
  std::vector<const XMLElement*> list;
  forEachCeng477Child(materials, {}, [&](const XMLElement* e, std::string_view name) {
    if (name != "material") return false;
    list.push_back(e);
    return true;
  });
  // From 2021 on the course marks mirrors with type="mirror", and then only those reflect.
  const bool typed = std::any_of(list.begin(), list.end(), [&](const XMLElement* e) { return hasAttribute(e, "type"); });
  bool numbered = true;  // ids 1..n in document order
  for (std::size_t k = 0; k < list.size(); ++k) {
    Material material = readCeng477Material(list[k], typed);
    numbered = numbered && material.id == std::to_string(k + 1);
    scene.materials.push_back(std::move(material));
  }
  if (!numbered)
    warn(materials->GetLineNum(), "material ids are not 1, 2, 3... in order: <Material>N</Material> in an object "
                                  "names the N-th <Material>, as the course's parser reads it, and they are renumbered so");
  for (std::size_t k = 0; k < scene.materials.size(); ++k) {
    Material& material = scene.materials[k];
    material.id = std::to_string(k + 1);
    materialIndex_.emplace(material.id, static_cast<std::uint32_t>(k));
    materialLines_.emplace(material.id, list[k]->GetLineNum());
  }
}

Material Loader::readCeng477Material(const XMLElement* e, bool typed) {
  Material material;
  material.id = attribute(e, "id");
  material.id.erase(0, material.id.find_first_not_of(" \t\r\n"));
  material.id.erase(material.id.find_last_not_of(" \t\r\n") + 1);
  const std::string type = attribute(e, "type");
  if (!type.empty() && type != "mirror")
    nonconforming(e->GetLineNum(), describe(e) + ": type=\"" + type + "\" is not a material rayview renders; read as a "
                                   "Blinn-Phong material");
  unsigned have = 0;
  forEachCeng477Child(e, {"ambientreflectance", "diffusereflectance", "specularreflectance", "phongexponent", "mirrorreflectance"},
                      [&](const XMLElement* c, std::string_view name) {
    if (name == "ambientreflectance") material.ambient = readColor(c), have |= 1;
    else if (name == "diffusereflectance") material.diffuse = readColor(c), have |= 2;
    else if (name == "specularreflectance") material.specular = readColor(c), have |= 4;
    else if (name == "mirrorreflectance") material.mirror = readColor(c);
    else if (name == "phongexponent") {
      const double p = readScalar(c, true);
      if (p < 0.0) fail(c->GetLineNum(), elementName(c) + ": must be >= 0, found " + trimmedText(c));
      material.phongExponent = static_cast<float>(p);
      have |= 8;
    } else {
      return false;
    }
    return true;
  });
  const char* names[] = {"<AmbientReflectance>", "<DiffuseReflectance>", "<SpecularReflectance>", "<PhongExponent>"};
  for (int i = 0; i < 4; ++i)
    if (!(have & (1u << i))) fail(e->GetLineNum(), describe(e) + " has no " + names[i]);
  if (typed && type != "mirror" && material.isMirror()) {
    warn(e->GetLineNum(), describe(e) + " has a <MirrorReflectance> but no type=\"mirror\": not a mirror (in a file that "
                          "marks its mirrors, the course reflects only those)");
    material.mirror = Color(0.0f);
  }
  return material;
}

void Loader::readCeng477Objects(const XMLElement* objects) {
  forEachCeng477Child(objects, {}, [&](const XMLElement* e, std::string_view name) {
    if (name == "mesh" || name == "triangle") {
      readCeng477Object(e, name == "triangle");
    } else {
      // Every child of <Objects> is an object; rayview's are triangles (SPEC section 1).
      if (firstDroppedObject_ == 0) firstDroppedObject_ = e->GetLineNum(), firstDroppedName_ = describe(e);
      nonconforming(e->GetLineNum(), elementName(e) + " is a CENG477 object rayview does not render (triangle meshes "
                                     "only): dropped, the image lacks it");
    }
    return true;
  });
}

bool Loader::readCeng477Object(const XMLElement* e, bool triangle) {
  PendingMesh mesh;
  mesh.line = e->GetLineNum();
  mesh.label = describe(e);
  const XMLElement* material = nullptr;
  const XMLElement* faces = nullptr;
  const std::string_view facesName = triangle ? "indices" : "faces";
  bool drop = false;
  forEachCeng477Child(e, {"material", facesName}, [&](const XMLElement* c, std::string_view name) {
    if (name == "material") material = c;
    else if (name == facesName) faces = c;
    else if (!drop) {
      // Transformations, textures...: drawn without them the object would be in the wrong place or colour.
      nonconforming(c->GetLineNum(), mesh.label + " has " + elementName(c) + ", which rayview does not read: the object "
                                     "is dropped, the image lacks it");
      drop = true;
    }
    return true;
  });
  if (drop) {
    if (firstDroppedObject_ == 0) firstDroppedObject_ = mesh.line, firstDroppedName_ = mesh.label;
    return false;
  }
  if (!material) fail(mesh.line, mesh.label + " has no <Material>");
  if (!faces) fail(mesh.line, mesh.label + " has no " + (triangle ? "<Indices>" : "<Faces>"));
  std::int64_t number = 0;
  readIntegers(material, 1, &number, 1, "a material number (1 for the first <Material>)");
  mesh.id = std::to_string(meshes_.size() + 1);
  mesh.materialId = std::to_string(number);
  mesh.materialIdLine = material->GetLineNum();
  mesh.faces = faces;
  if (triangle) readCeng477Triangle(faces, mesh);
  else if (hasAttribute(faces, "plyFile")) readPlyFaces(mesh, attribute(faces, "plyFile"));
  else readFaces(mesh);
  meshes_.push_back(std::move(mesh));
  return true;
}

void Loader::readCeng477Triangle(const XMLElement* indices, PendingMesh& mesh) {
  // The stream's faces fill the triangles mesh by mesh: one added here would shift them.
  if (streamed_ && streamed_->triangleCount != 0) throw StreamAbandoned{};
  std::int64_t v[3];
  readIntegers(indices, 3, v, 0, "3 vertex indices");
  SceneArray<Triangle>& triangles = result_.scene.triangles;
  if (triangles.size() > static_cast<std::size_t>(UINT32_MAX / 2) || v[0] > INT32_MAX || v[1] > INT32_MAX || v[2] > INT32_MAX)
    fail(indices->GetLineNum(), mesh.label + ": too many triangles, or an index beyond any vertex");
  mesh.firstTriangle = static_cast<std::uint32_t>(triangles.size());
  mesh.triangleCount = 1;
  Triangle t;
  for (int k = 0; k < 3; ++k) {
    t.vertex[k] = static_cast<std::uint32_t>(v[k]);
    vertexRange_.add(v[k], indices->GetLineNum());
  }
  result_.scene.addFace(t);
}

void Loader::readPlyFaces(PendingMesh& mesh, const std::string& plyFile) {
  if (streamed_ && streamed_->triangleCount != 0) throw StreamAbandoned{};
  const XMLElement* faces = mesh.faces;
  const int line = faces->GetLineNum();
  const std::string written = "<Faces plyFile=\"" + plyFile + "\">";
  const StreamedBlock* block = streamedBlock(faces, Tag::Faces);  // only ever an empty one here
  if (!block && !trimmedText(faces).empty())
    nonconforming(line, written + " also has faces written out: they are ignored, the faces are the PLY file's");
  const fs::path path = fs::path(plyFile).is_absolute() ? fs::path(plyFile) : baseDirectory_ / plyFile;
  detail::PlyMesh ply;
  try {
    ply = detail::readPlyFile(path);
  } catch (const detail::PlyError& error) {
    fail(line, written + ": the PLY file " + path.string() + ": " + error.message);
  }
  if (ply.skippedFaces > 0)
    warn(line, written + ": " + plural(ply.skippedFaces, "face", "faces") + " of fewer than three vertices skipped");
  SceneArray<Triangle>& triangles = result_.scene.triangles;
  if (plyVertices_.size() + ply.vertices.size() > static_cast<std::size_t>(INT32_MAX) ||
      triangles.size() + ply.triangles.size() > static_cast<std::size_t>(UINT32_MAX / 2))
    fail(line, written + ": too many vertices or triangles");
  // File numbering (1-based) within the PLY meshes' vertices; finishCeng477 moves them past <VertexData>'s.
  const std::uint32_t base = static_cast<std::uint32_t>(plyVertices_.size()) + 1;
  plyVertices_.insert(plyVertices_.end(), ply.vertices.begin(), ply.vertices.end());
  mesh.fromPly = true;
  mesh.firstTriangle = static_cast<std::uint32_t>(triangles.size());
  mesh.triangleCount = static_cast<std::uint32_t>(ply.triangles.size());
  triangles.reserve(triangles.size() + ply.triangles.size());
  for (const Triangle& f : ply.triangles)
    result_.scene.addFace(Triangle{{f.vertex[0] + base, f.vertex[1] + base, f.vertex[2] + base}});
}

void Loader::finishCeng477() {
  // An image of the background alone is no rendering of the scene.
  if (meshes_.empty() && firstDroppedObject_ != 0)
    fail(firstDroppedObject_, "no object of the scene can be rendered: rayview renders triangle meshes only, and the "
                              "objects here are not (the first is " + firstDroppedName_ + ")");
  if (plyVertices_.empty()) return;
  Scene& scene = result_.scene;
  const std::size_t fileVertices = scene.vertices.size();
  if (fileVertices + plyVertices_.size() > static_cast<std::size_t>(INT32_MAX))
    fail(0, "too many vertices (<VertexData> and the PLY files together)");
  for (const PendingMesh& mesh : meshes_)
    for (std::uint32_t i = 0; i < mesh.triangleCount; ++i) {
      Triangle& t = scene.triangles[mesh.firstTriangle + i];
      for (int c = 0; c < 3; ++c) {
        if (mesh.fromPly) t.vertex[c] += static_cast<std::uint32_t>(fileVertices);
        // Faces written in the file index <VertexData> only, never a PLY file's vertices.
        else if (t.vertex[c] > fileVertices)
          indexOutOfRange(mesh, std::size_t{i} * 3 + c, "vertex", t.vertex[c], 1, static_cast<std::int64_t>(fileVertices));
      }
    }
  scene.vertices.insert(scene.vertices.end(), plyVertices_.begin(), plyVertices_.end());
  SceneArray<glm::dvec3>().swap(plyVertices_);
}

}  // namespace rayview::scene_loading
