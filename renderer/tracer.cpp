#include "rayview/tracer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include <glm/geometric.hpp>

#include "isa_clones.h"
#include "light_samples.h"
#include "rayview/light_types.h"
#include "rayview/prepared_scene.h"
#include "rayview/texel_lookup.h"
#include "ray_offset.h"
#include "point_light_lanes.h"
#include "specular_power.h"

namespace rayview {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

glm::vec3 toFloat(const glm::dvec3& v) { return glm::vec3(v); }

// Shadow rays stop just short of the light: "up to (but not including) it".
double justBefore(double distance) { return distance * (1.0 - 1e-6); }

// Every light of one type, each asked for its light directions at `p` (see light_type.h).
template <class Shadings, class Visit>
void illuminateAll(const Shadings& lights, const glm::dvec3& p, std::uint32_t pixelSeed, Visit& visit) {
  for (const auto& light : lights) light.illuminate(p, pixelSeed, visit);
}

// Seeds the pixel's stratified offsets and light samples.
std::uint32_t seedOfPixel(int i, int j) {
  return hash32(static_cast<std::uint32_t>(j) * 0x9E3779B1U + static_cast<std::uint32_t>(i));
}

}  // namespace

ShadingGeometry prepareShadingGeometry(const SceneGeometry&, const glm::dvec3& origin) { return {origin}; }

// A hit's colour is local + mirror * (colour of the next hit), then blended with the texture:
//   c = tf * texel + (1 - tf) * (local + mirror * next).
// The path is followed forward (no recursion, so no depth can exhaust the stack) and folded backward in
// exactly this order, which is the arithmetic of the recursive definition.
struct Tracer::PathVertex {
  Color local{0.0f};
  Color mirror{0.0f};      // weight of the next hit
  Color texel{0.0f};
  float textureFactor = 0.0f;
  bool continues = false;  // a mirror ray leaves this hit
  bool textured = false;
};

namespace {

// Paths in a block are followed together to this depth; a lane still going on then finishes alone, so the
// block's buffer stays small (16 lanes x this many vertices) whatever the scene's depth.
constexpr int kBlockDepth = 16;

// The colour at vertex `first` of a path from its vertices first..last (vertexAt(k) gives vertex k), folded
// backward from `next`, the colour of the path beyond `last` (nothing: 0).
template <class VertexAt>
Color foldPath(int first, int last, VertexAt&& vertexAt, Color next = Color(0.0f)) {
  for (int k = last; k >= first; --k) {
    const auto& v = vertexAt(k);
    Color color = v.local;
    if (v.continues) color += v.mirror * next;
    if (v.textured) color = v.textureFactor * v.texel + (1.0f - v.textureFactor) * color;
    next = color;
  }
  return next;
}

}  // namespace

// A light direction's contribution counts unless its shadow ray (when it has one) is occluded. The ray comes as
// its parts, so that the queue below writes them straight into its entry: a Ray built on the stack and copied
// whole is read with wide loads of narrow stores, which miss store forwarding (~10 % of a render, mirror_scene).
struct Tracer::ImmediateShadows {
  const Accel& accel;
  void light(const Color& contribution, int /*sequence*/, Color& color) const { color += contribution; }
  void light(const Color& contribution, int /*sequence*/, Color& color, const glm::dvec3& origin,
             const glm::dvec3& direction, double tFar, std::uint32_t excluded) const {
    if (!accel.occluded(Ray{origin, direction, 0.0, tFar, excluded})) color += contribution;
  }
};

// The same decisions, queued: resolve() casts the queued shadow rays in packets (the rays of one light
// direction from the block's hits together, the most coherent) and adds the contributions that count in the
// order each hit queued them, which is the order ImmediateShadows adds them in: the same colours, bit for bit.
struct Tracer::QueuedShadows {
  struct Entry {
    Color contribution;
    int lane;
    int sequence;  // the light direction's place in its hit's shading
    bool hasRay;
    Ray ray;
  };
  // entries[0 .. count): grown, never shrunk, so that an entry is not value-initialised each time (a `rep stos`
  // of 96 bytes per shadow ray, 10 % of the point lights' time); every field read is written by add().
  std::vector<Entry> entries;
  std::size_t count = 0;
  std::vector<int> order;
  std::vector<int> starts;
  std::vector<char> occluded;
  Ray packet[kRayPacket];
  int lane = 0;

  void light(const Color& contribution, int sequence, Color&) { add(lane, sequence, contribution, false); }
  void light(const Color& contribution, int sequence, Color&, const glm::dvec3& origin, const glm::dvec3& direction,
             double tFar, std::uint32_t excluded) {
    Ray& ray = *add(lane, sequence, contribution, true);
    ray.origin = origin;
    ray.direction = direction;
    ray.tNear = 0.0;
    ray.tFar = tFar;
    ray.excludedTriangle = excluded;
  }

  // An entry for `laneOf`; its shadow ray, when it has one, is the caller's to write (field by field).
  Ray* add(int laneOf, int sequence, const Color& contribution, bool hasRay) {
    if (count == entries.size()) entries.resize(std::max<std::size_t>(64, 2 * entries.size()));
    Entry& e = entries[count++];
    e.contribution = contribution;
    e.lane = laneOf;
    e.sequence = sequence;
    e.hasRay = hasRay;
    return &e.ray;
  }

  // Adds each lane's contributions to colorOf(lane).
  template <class ColorOf>
  void resolve(const Accel& accel, ColorOf&& colorOf) {
    // The entries with a ray by sequence, then lane (a counting sort: no allocation once grown).
    int last = -1, rays = 0;
    const Entry* const end = entries.data() + count;
    for (const Entry* e = entries.data(); e != end; ++e)
      if (e->hasRay) {
        last = std::max(last, e->sequence);
        ++rays;
      }
    starts.assign(static_cast<std::size_t>(last) + 2, 0);
    for (const Entry* e = entries.data(); e != end; ++e)
      if (e->hasRay) ++starts[e->sequence + 1];
    for (std::size_t s = 1; s < starts.size(); ++s) starts[s] += starts[s - 1];
    order.resize(rays);
    for (int e = 0; e < static_cast<int>(count); ++e)
      if (entries[e].hasRay) order[starts[entries[e].sequence]++] = e;
    occluded.assign(count, 0);
    for (std::size_t first = 0; first < order.size(); first += kRayPacket) {
      const int n = static_cast<int>(std::min<std::size_t>(kRayPacket, order.size() - first));
      bool answers[kRayPacket];
      for (int m = 0; m < n; ++m) packet[m] = entries[order[first + m]].ray;
      accel.occludedMany(packet, n, answers);
      for (int m = 0; m < n; ++m) occluded[order[first + m]] = answers[m];
    }
    for (std::size_t e = 0; e < count; ++e)
      if (!occluded[e]) colorOf(entries[e].lane) += entries[e].contribution;
    count = 0;
  }
};

Tracer::Tracer(const Scene& scene, const Accel& accel, const ShadingGeometry& shading, const RenderSettings& settings)
    : Tracer(scene.parameters(), scene.geometry(), accel, shading, settings) {}

Tracer::Tracer(const SceneParameters& parameters, const PreparedGeometry& geometry, const RenderSettings& settings)
    : Tracer(parameters, *geometry.source, *geometry.accel, geometry.shading, settings) {}

Tracer::Tracer(const SceneParameters& parameters, const SceneGeometry& meshes, const Accel& accel,
               const ShadingGeometry& shading, const RenderSettings& settings)
    : parameters_(parameters), meshes_(meshes), accel_(accel), shading_(shading), settings_(settings) {
  basis_ = cameraBasis(parameters.camera);
  const Camera& camera = parameters.camera;
  columnParts_.resize(static_cast<std::size_t>(camera.width));
  rowParts_.resize(static_cast<std::size_t>(camera.height));
  for (int i = 0; i < camera.width; ++i) columnParts_[i] = pixelColumnPart(camera, basis_, i);
  for (int j = 0; j < camera.height; ++j) rowParts_[j] = pixelRowPart(camera, basis_, j);
  eyeRelative_ = parameters.camera.position - accel.origin();
  cull_.emplace(camera, basis_, eyeRelative_, accel.boxes());
  lights_ = parameters.lights.prepare(accel.origin(), settings);
  pointLightsOnly_ = std::get<std::vector<TriangularLightShading>>(lights_).empty();
  for (const Material& material : parameters.materials) {
    textures_.push_back(meshes.textureOf(material));
    emissionMaps_.push_back(meshes.textureNamed(material.emissionImage));
    metalRoughMaps_.push_back(meshes.textureNamed(material.metalRoughImage));
    anyMetalRough_ |= metalRoughMaps_.back() != nullptr;
  }
  for (const Mesh& mesh : meshes.meshes) {
    meshStarts_.push_back(mesh.firstTriangle);
    meshMaterials_.push_back(mesh.material);
  }
  if (meshStarts_.empty()) meshStarts_.push_back(0), meshMaterials_.push_back(0);
}

const Material& Tracer::materialOf(std::uint32_t triangle) const {
  const std::uint32_t* starts = meshStarts_.data();
  const std::size_t mesh = lastRangeAtOrBefore(meshStarts_.size(), triangle, [&](std::size_t k) { return starts[k]; });
  return parameters_.materials[meshMaterials_[mesh]];
}

int Tracer::pixelSamples() const { return std::clamp(settings_.pixelSamples, 1, kMaxPixelSamples); }

Color Tracer::tracePixel(int i, int j, RayCounts& counts) const {
  const int samples = pixelSamples();
  if (samples == 1) return traceSample(i, j, 0, counts);  // the pixel's centre, as the course's images
  Color sum(0.0f);
  for (int k = 0; k < samples; ++k) sum += traceSample(i, j, k, counts);
  return sum / static_cast<float>(samples);
}

Color Tracer::traceSample(int i, int j, int k, RayCounts& counts) const {
  std::uint32_t seed = 0;
  Ray ray;
  sampleRay(i, j, k, seed, ray);
  return traceCameraRay(ray, seed, counts);
}

void Tracer::sampleRay(int i, int j, int k, std::uint32_t& seed, Ray& ray) const {
  const std::uint32_t pixelSeed = seedOfPixel(i, j);
  const int samples = pixelSamples();
  if (samples == 1) {
    seed = pixelSeed;
    return cameraRay(i, j, ray);
  }
  const glm::vec2 offset = pixelSampleOffset(k, samples, pixelSeed);
  // pixelDirection aims at i + 0.5: shift by the offset from the centre. Light samples vary per camera ray.
  seed = hash32(pixelSeed + static_cast<std::uint32_t>(k));
  cameraRay(i + (offset.x - 0.5), j + (offset.y - 0.5), ray);
}

void Tracer::tracePixels(const PixelXY* pixels, int count, Color* out, RayCounts& counts) const {
  const int samples = pixelSamples();
  if (samples == 1) return traceSamples(pixels, count, 0, out, counts);
  if (cameraMisses(pixels, count)) {
    // The background as each pixel's samples would sum it, bit for bit.
    for (int n = 0; n < count; ++n) {
      Color sum(0.0f);
      for (int k = 0; k < samples; ++k) sum += parameters_.background;
      out[n] = sum / static_cast<float>(samples);
    }
    counts.camera += static_cast<std::uint64_t>(count) * static_cast<std::uint64_t>(samples);
    return;
  }
  // Each pixel's samples together (as coherent as rays get), summed in tracePixel's order.
  for (int n = 0; n < count; ++n) {
    Color sum(0.0f);
    for (int first = 0; first < samples; first += kRayPacket) {
      const int m = std::min(kRayPacket, samples - first);
      thread_local Ray rays[kRayPacket];  // every field written by sampleRay: no zeroing per packet
      std::uint32_t seeds[kRayPacket];
      Color colors[kRayPacket];
      for (int k = 0; k < m; ++k) sampleRay(pixels[n].x, pixels[n].y, first + k, seeds[k], rays[k]);
      traceCameraRays(rays, seeds, m, colors, counts);
      for (int k = 0; k < m; ++k) sum += colors[k];
    }
    out[n] = sum / static_cast<float>(samples);
  }
}

void Tracer::traceSamples(const PixelXY* pixels, int count, int k, Color* out, RayCounts& counts) const {
  for (int first = 0; first < count; first += kRayPacket) {
    const int n = std::min(kRayPacket, count - first);
    if (cameraMisses(pixels + first, n)) {
      std::fill_n(out + first, n, parameters_.background);
      counts.camera += static_cast<std::uint64_t>(n);
      continue;
    }
    thread_local Ray rays[kRayPacket];  // every field written by sampleRay: no zeroing per packet (~1 KB)
    std::uint32_t seeds[kRayPacket];
    for (int m = 0; m < n; ++m) sampleRay(pixels[first + m].x, pixels[first + m].y, k, seeds[m], rays[m]);
    traceCameraRays(rays, seeds, n, out + first, counts);
  }
}

bool Tracer::cameraMisses(const PixelXY* pixels, int count) const {
  if (count <= 0) return false;
  int x0 = pixels[0].x, x1 = x0, y0 = pixels[0].y, y1 = y0;
  for (int n = 1; n < count; ++n) {
    x0 = std::min(x0, pixels[n].x), x1 = std::max(x1, pixels[n].x);
    y0 = std::min(y0, pixels[n].y), y1 = std::max(y1, pixels[n].y);
  }
  // Half a pixel around the centres: every sample's ray (sampleRay's offsets are within it).
  return cull_->misses(x0 - 0.5, x1 + 0.5, y0 - 0.5, y1 + 0.5);
}

void Tracer::traceCameraRays(const Ray* rays, const std::uint32_t* seeds, int count, Color* out,
                             RayCounts& counts) const {
  thread_local std::optional<Hit> hits[kRayPacket];  // closestHits sets each of the count: no zeroing per packet
  counts.camera += static_cast<std::uint64_t>(count);
  accel_.closestHits(rays, count, hits);
  tracePaths(rays, hits, seeds, count, out, counts);
}

void Tracer::cameraRay(double i, double j, Ray& ray) const {
  setCameraRay(pixelDirection(parameters_.camera, basis_, i, j), ray);
}

void Tracer::cameraRay(int i, int j, Ray& ray) const {
  if (i < 0 || j < 0 || i >= static_cast<int>(columnParts_.size()) || j >= static_cast<int>(rowParts_.size()))
    return cameraRay(static_cast<double>(i), static_cast<double>(j), ray);
  setCameraRay(columnParts_[i] + rowParts_[j], ray);
}

void Tracer::setCameraRay(const glm::dvec3& direction, Ray& ray) const {
  ray.origin = eyeRelative_;
  ray.direction = glm::normalize(direction);
  ray.tNear = 0.0;
  ray.tFar = kInfinity;
  ray.excludedTriangle = kNoTriangle;
}

Color Tracer::traceCameraRay(const Ray& ray, std::uint32_t seed, RayCounts& counts) const {
  ++counts.camera;
  if (std::optional<Hit> hit = accel_.closestHit(ray)) return tracePath(ray, *hit, seed, counts);
  return parameters_.background;
}

Color Tracer::tracePath(const Ray& cameraRay, const Hit& firstHit, std::uint32_t pixelSeed, RayCounts& counts) const {
  return followPath(cameraRay, firstHit, 0, pixelSeed, counts);
}

RAYVIEW_HOT Color Tracer::followPath(const Ray& firstRay, const Hit& firstHit, int firstDepth,
                                     std::uint32_t pixelSeed, RayCounts& counts) const {
  constexpr int kInline = 16;  // deeper paths (facing mirrors) spill to the heap
  PathVertex inlineVertices[kInline];
  std::vector<PathVertex> spilled;
  // Vertex of depth firstDepth + k.
  auto vertexAt = [&](int k) -> PathVertex& {
    if (k < kInline) return inlineVertices[k];
    if (static_cast<std::size_t>(k - kInline) >= spilled.size()) spilled.resize(spilled.size() * 2 + kInline);
    return spilled[k - kInline];
  };

  ImmediateShadows shadows{accel_};
  Ray ray = firstRay;
  Hit hit = firstHit;
  int last = 0;
  for (int k = 0;; ++k) {
    Ray next;
    PathVertex& v = vertexAt(k);
    shadeHit(ray, hit, firstDepth + k, pixelSeed, counts, shadows, v, next);
    last = k;
    if (!v.continues) break;
    ++counts.reflection;
    std::optional<Hit> nextHit = accel_.closestHit(next);
    if (!nextHit) break;  // a reflected ray that hits nothing adds nothing (course reference)
    ray = next;
    hit = *nextHit;
  }
  return foldPath(0, last, vertexAt);
}

RAYVIEW_HOT void Tracer::tracePaths(const Ray* cameraRays, const std::optional<Hit>* firstHits,
                                    const std::uint32_t* pixelSeeds, int count, Color* out, RayCounts& counts) const {
  // tracePath for each lane with a hit, every lane's depth d before any lane's depth d + 1.
  // The buffers stay with the thread: no allocation per block once they have grown (~10 % of car's time).
  // So do the lanes' mirror rays and hits (on the stack, their initialisation was ~5 KB of zeroing per block).
  thread_local std::vector<PathVertex> vertices;  // vertex of depth d of lane m at d * kRayPacket + m
  thread_local QueuedShadows shadows;
  struct Lanes {
    Ray mirrors[kRayPacket], next[kRayPacket];
    std::optional<Hit> nextHits[kRayPacket];
  };
  thread_local Lanes lanes;
  auto& [mirrors, next, nextHits] = lanes;
  // Each lane's ray and hit at this depth, where they are (the camera's or the last mirror packet's): copied, a
  // hit just written field by field was read with wide loads, which miss store forwarding.
  const Ray* rays[kRayPacket];
  const Hit* hits[kRayPacket];
  shadows.count = 0;
  int last[kRayPacket];
  int active[kRayPacket];
  int activeCount = 0;
  for (int m = 0; m < count; ++m) {
    last[m] = -1;
    if (!firstHits[m]) continue;
    rays[m] = &cameraRays[m];
    hits[m] = &*firstHits[m];
    active[activeCount++] = m;
  }
  int depth = 0;
  for (; activeCount > 0 && depth < kBlockDepth; ++depth) {
    // Grown, never shrunk: resizing down and up again value-initialised each depth's row (a memset per depth and
    // block), though every vertex read is one this block wrote.
    if (vertices.size() < static_cast<std::size_t>(depth + 1) * kRayPacket)
      vertices.resize(static_cast<std::size_t>(depth + 1) * kRayPacket);
    PathVertex* row = &vertices[static_cast<std::size_t>(depth) * kRayPacket];
    LitPoint lit[kRayPacket];
    for (int a = 0; a < activeCount; ++a) {
      const int m = active[a];
      shadows.lane = m;
      shadeHit(*rays[m], *hits[m], depth, pixelSeeds[m], counts, shadows, row[m], mirrors[m],
               pointLightsOnly_ ? &lit[a] : nullptr);
      lit[a].lane = m;
      last[m] = depth;
    }
    if (pointLightsOnly_) shadePointLights(lit, activeCount, counts, shadows);
    shadows.resolve(accel_, [&](int m) -> Color& { return row[m].local; });
    // The lanes whose path goes on: their mirror rays as one packet.
    int going[kRayPacket];
    int goingCount = 0;
    for (int a = 0; a < activeCount; ++a) {
      const int m = active[a];
      if (!row[m].continues) continue;
      next[goingCount] = mirrors[m];
      going[goingCount++] = m;
    }
    counts.reflection += static_cast<std::uint64_t>(goingCount);
    if (goingCount > 0) accel_.closestHits(next, goingCount, nextHits);
    activeCount = 0;
    for (int g = 0; g < goingCount; ++g) {
      if (!nextHits[g]) continue;  // a reflected ray that hits nothing adds nothing (course reference)
      const int m = going[g];
      rays[m] = &next[g];  // next and nextHits are rewritten only after the next depth's shading
      hits[m] = &*nextHits[g];
      active[activeCount++] = m;
    }
  }
  // Lanes still going on at kBlockDepth: the rest of each path alone, from its next hit, then folded into the
  // block's vertices (the same arithmetic, in the same order, as one path followed to its end).
  Color beyond[kRayPacket];
  for (int m = 0; m < count; ++m) beyond[m] = Color(0.0f);
  for (int a = 0; a < activeCount; ++a) {
    const int m = active[a];
    beyond[m] = followPath(*rays[m], *hits[m], depth, pixelSeeds[m], counts);
  }
  for (int m = 0; m < count; ++m) {
    const auto vertexOf = [&](int k) -> const PathVertex& { return vertices[static_cast<std::size_t>(k) * kRayPacket + m]; };
    out[m] = last[m] < 0 ? parameters_.background : foldPath(0, last[m], vertexOf, beyond[m]);
  }
}

SecondaryStart Tracer::secondaryStart() const {
  SecondaryStart start;
  start.excludeHit = settings_.secondaryRayStart == SecondaryRayStart::ExcludeHitTriangle;
  start.fixedEpsilon = parameters_.shadowRayEpsilon.has_value();
  start.epsilon = start.fixedEpsilon ? *parameters_.shadowRayEpsilon : 0.0;
  start.eye = eyeRelative_;
  return start;
}

void Tracer::shadePointLights(const LitPoint* points, int count, RayCounts& counts, QueuedShadows& shadows) const {
  const auto& lights = std::get<std::vector<PointLightShading>>(lights_);
  const SecondaryStart start = secondaryStart();
  for (int first = 0; first < count; first += 4) {
    const LitPoint* four = points + first;
    shadePointLightsFour(four, std::min(4, count - first), lights, start,
                         [&](int j, int place, const Color& contribution, bool hasRay) {
                           if (hasRay) ++counts.shadow;
                           return shadows.add(four[j].lane, place, contribution, hasRay);
                         });
  }
}

namespace {

// A hit's point and normals, relative to the traversal's origin.
struct SurfacePoint {
  glm::dvec3 p;   // in double from the barycentrics: on the triangle's plane to double rounding, whatever the ray was
  glm::dvec3 ng;  // the face normal from the world positions: exact whatever the origin
  glm::vec3 n;    // the shading normal: the vertex normals interpolated where the face has them, else ng
};

// A two-sided material's face seen from behind (twoSided, the ray along `direction` meeting its back) is shaded as
// its front: both normals turned toward the viewer, so the lights, the mirror ray and the secondary rays' offset
// all work on the side the ray arrived at. One-sided materials (every handout scene's) keep the normals as they are.
inline SurfacePoint surfaceAt(const SceneGeometry& meshes, const glm::dvec3& origin, const Hit& hit,
                              const FaceAttributes& attributes, bool twoSided, const glm::dvec3& direction) {
  const Triangle& triangle = meshes.triangles[hit.triangle];
  const auto b1 = static_cast<float>(hit.b1), b2 = static_cast<float>(hit.b2);
  const float b0 = 1.0f - b1 - b2;
  const glm::dvec3& w0 = meshes.vertices[triangle.vertex[0]];
  const glm::dvec3& w1 = meshes.vertices[triangle.vertex[1]];
  const glm::dvec3& w2 = meshes.vertices[triangle.vertex[2]];
  const glm::dvec3 a = w0 - origin;
  SurfacePoint s;
  s.p = a + hit.b1 * ((w1 - origin) - a) + hit.b2 * ((w2 - origin) - a);
  const glm::dvec3 cross = glm::cross(w1 - w0, w2 - w0);
  const double crossLength = glm::length(cross);
  s.ng = crossLength > 0.0 ? cross / crossLength : glm::dvec3(0.0, 0.0, 1.0);
  s.n = toFloat(s.ng);
  if (attributes.hasNormals()) {
    const glm::vec3 interpolated = b0 * meshes.normals[attributes.normal[0]] +
                                   b1 * meshes.normals[attributes.normal[1]] + b2 * meshes.normals[attributes.normal[2]];
    const float length = glm::length(interpolated);
    if (length > 0.0f && std::isfinite(length)) s.n = interpolated / length;
  }
  if (twoSided && glm::dot(s.ng, direction) > 0.0) [[unlikely]] {
    s.ng = -s.ng;
    s.n = -s.n;
  }
  return s;
}

}  // namespace

template <class Shadows>
void Tracer::shadeHit(const Ray& ray, const Hit& hit, int depth, std::uint32_t pixelSeed, RayCounts& counts,
                      Shadows& shadows, PathVertex& v, Ray& mirrorRay, LitPoint* lit) const {
  const Material& material = materialOf(hit.triangle);
  const FaceAttributes& attributes = meshes_.attributesOf(hit.triangle);
  const SurfacePoint surface = surfaceAt(meshes_, shading_.origin, hit, attributes, material.twoSided, ray.direction);
  const glm::dvec3& pExact = surface.p;
  const glm::dvec3& ngExact = surface.ng;
  const glm::vec3 n = surface.n;
  const glm::dvec3 dExact = glm::normalize(ray.direction);
  const glm::vec3 toEye = -toFloat(dExact);
  const SecondaryStart start = secondaryStart();
  // Where a secondary ray leaving the surface along `direction` starts, and the triangle it must not hit.
  auto secondaryOrigin = [&](const glm::dvec3& direction) {
    if (start.excludeHit) return pExact;
    return start.fixedEpsilon ? pExact + start.epsilon * ngExact
                              : offsetRayOrigin(pExact, start.eye, ngExact, direction);
  };
  const std::uint32_t excluded = start.excludeHit ? hit.triangle : kNoTriangle;

  // `v` may be a block's slot from an earlier block: every field foldPath reads is set.
  v.continues = false;
  v.textured = false;
  PhongTerms terms = termsAt(material, attributes, hit);
  // The mirror ray before the shading: 1.05-1.07x faster renders of the scenes with mirrors (docs/PERFORMANCE.md,
  // "Shading"), its normalisation (a square root, then a division) overlapping the shading. A metallic-roughness
  // texel can make the mirror black where the material's average is not: no ray there.
  if (material.isMirror() && depth < parameters_.maxRayDepth && terms.mirror != Color(0.0f)) {
    const glm::dvec3 nExact(n);
    const glm::dvec3 r = glm::normalize(dExact - 2.0 * glm::dot(dExact, nExact) * nExact);
    mirrorRay.origin = secondaryOrigin(r);
    mirrorRay.direction = r;
    mirrorRay.tNear = 0.0;
    mirrorRay.tFar = kInfinity;
    mirrorRay.excludedTriangle = excluded;
    v.mirror = terms.mirror;
    v.continues = true;
  }

  Color& color = v.local;
  color = unlitColor(material, attributes, hit, terms);

  // One light direction: its Blinn-Phong terms, then (when they add anything) the shadow ray toward `target`
  // (stopping just before it), or along `l` without end.
  int sequence = 0;
  auto addLight = [&](const glm::dvec3& l, const Color& irradiance, const glm::dvec3* target) {
    const int place = sequence++;
    const glm::vec3 toLight = toFloat(l);
    const Color diffuse = terms.diffuse * irradiance * std::max(0.0f, glm::dot(n, toLight));
    const glm::vec3 h = glm::normalize(toLight + toEye);
    const float specular = specularPower(std::max(0.0f, glm::dot(n, h)), terms.phongExponent);
    const Color contribution = diffuse + terms.specular * irradiance * specular;
    if (contribution == Color(0.0f)) return;  // no shadow ray for light that would add nothing
    const glm::dvec3 origin = secondaryOrigin(l);
    if (!target) {
      ++counts.shadow;
      return shadows.light(contribution, place, color, origin, l, kInfinity, excluded);
    }
    const glm::dvec3 toTarget = *target - origin;
    const double length = glm::length(toTarget);
    if (!(length > 0.0)) return shadows.light(contribution, place, color);
    ++counts.shadow;
    shadows.light(contribution, place, color, origin, toTarget / length, justBefore(length), excluded);
  };

  if (lit) {
    lit->p = pExact;
    lit->ng = ngExact;
    lit->n = n;
    lit->toEye = toEye;
    lit->diffuse = terms.diffuse;
    lit->specular = terms.specular;
    lit->phongExponent = terms.phongExponent;
    lit->triangle = hit.triangle;
  } else {
    std::apply([&](const auto&... byType) { ((illuminateAll(byType, pExact, pixelSeed, addLight)), ...); }, lights_);
  }

  if (material.textureFactor != 0.0f && attributes.hasTexCoords()) applyTexture(material, attributes, hit, v);
}

PhongTerms Tracer::termsAt(const Material& material, const FaceAttributes& attributes, const Hit& hit) const {
  if (!anyMetalRough_) [[likely]]
    return phongTermsOf(material);
  const Texture* map = metalRoughMaps_[static_cast<std::size_t>(&material - parameters_.materials.data())];
  if (!map || !attributes.hasTexCoords()) return phongTermsOf(material);
  const Color texel = sampleTexture(*map, attributes, hit) / 255.0f;
  return metalRoughTerms(material.baseColor, material.metallic * texel.z, material.roughness * texel.y);
}

Color Tracer::unlitColor(const Material& material, const FaceAttributes& attributes, const Hit& hit,
                         PhongTerms& terms) const {
  if (!meshes_.vertexColors.empty()) {
    const Color tint = vertexColorAt(hit);
    terms.ambient *= tint;
    terms.diffuse *= tint;
  }
  Color color = terms.ambient * parameters_.ambientLight;
  if (material.emits()) color += emissionAt(material, attributes, hit);
  return color;
}

Color Tracer::vertexColorAt(const Hit& hit) const {
  const Triangle& t = meshes_.triangles[hit.triangle];
  const auto b1 = static_cast<float>(hit.b1), b2 = static_cast<float>(hit.b2);
  const std::vector<Color>& c = meshes_.vertexColors;
  return (1.0f - b1 - b2) * c[t.vertex[0]] + b1 * c[t.vertex[1]] + b2 * c[t.vertex[2]];
}

Color Tracer::emissionAt(const Material& material, const FaceAttributes& attributes, const Hit& hit) const {
  const Texture* map = emissionMaps_[static_cast<std::size_t>(&material - parameters_.materials.data())];
  if (!map || !attributes.hasTexCoords()) return material.emission;
  return material.emission * (sampleTexture(*map, attributes, hit) / 255.0f);
}

void Tracer::applyTexture(const Material& material, const FaceAttributes& attributes, const Hit& hit,
                          PathVertex& v) const {
  const Texture* texture = textures_[static_cast<std::size_t>(&material - parameters_.materials.data())];
  if (!texture) return;
  v.textured = true;
  v.textureFactor = material.textureFactor;
  v.texel = sampleTexture(*texture, attributes, hit);
}

// Texture lookup at the texel texelIndex gives (rayview/texel_lookup.h); black where uv is not finite.
Color Tracer::sampleTexture(const Texture& texture, const FaceAttributes& face, const Hit& hit) const {
  const std::size_t at =
      texelIndex(texture, meshes_.texCoords, face, static_cast<float>(hit.b1), static_cast<float>(hit.b2));
  if (at == kNoTexel) return Color(0.0f);
  const std::uint8_t* texel = &texture.rgb[at * 3];
  return Color(texel[0], texel[1], texel[2]);
}

}  // namespace rayview
