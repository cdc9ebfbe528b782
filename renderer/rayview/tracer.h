#pragma once
// The Whitted integrator (SPEC sections 4-6): ambient + Blinn-Phong with I/d^2, hard shadows, recursive
// mirrors, texture blend, triangular lights. One Tracer per render: it reads the scene and settings and
// never changes them, so any number of threads may call tracePixel() at once.

#include <cstdint>
#include <vector>

#include "rayview/accel.h"
#include "rayview/camera_rays.h"
#include "rayview/render_settings.h"
#include "rayview/scene.h"

namespace rayview {

// Rays traced, by kind.
struct RayCounts {
  std::uint64_t camera = 0;
  std::uint64_t shadow = 0;
  std::uint64_t reflection = 0;

  std::uint64_t total() const { return camera + shadow + reflection; }
  RayCounts& operator+=(const RayCounts& o) {
    camera += o.camera;
    shadow += o.shadow;
    reflection += o.reflection;
    return *this;
  }
};

// Geometry relative to the accelerator's origin, computed once per scene load.
struct ShadingGeometry {
  std::vector<glm::dvec3> vertices;    // scene vertices minus origin, in double: hit points lie on the plane
  std::vector<glm::dvec3> faceNormals; // normalize((v2-v1) x (v3-v1)), never flipped
};

ShadingGeometry prepareShadingGeometry(const Scene& scene, const glm::dvec3& origin);

// Clamp to [0, 255] and round to nearest; NaN becomes 0.
std::uint8_t quantizeChannel(float value);

struct PreparedGeometry;

class Tracer {
 public:
  // Camera, lights, materials and depth come from `scene`; triangles, normals, texture coordinates and the
  // texture from the scene the geometry was prepared from. So the viewer's per-edit snapshot can be a
  // parameter-only copy (see parametersOf) and an edit never copies the meshes.
  Tracer(const Scene& scene, const PreparedGeometry& geometry, const RenderSettings& settings);
  // Everything from `scene`, which must be the scene `accel` and `geometry` were built from.
  Tracer(const Scene& scene, const Accel& accel, const ShadingGeometry& geometry, const RenderSettings& settings);

  // Radiance (0..255 units, unclamped) of pixel (column i, row j from the top).
  Color tracePixel(int i, int j, RayCounts& counts) const;

  int maxDepth() const { return maxDepth_; }

 private:
  struct TriangularLightFrame {
    glm::dvec3 v1, v2, v3, centroid, normal;  // normal = n_L, the side the light leaves
    Color intensity;
  };

  Color trace(const Ray& ray, int depth, std::uint32_t pixelSeed, RayCounts& counts) const;
  Color shadeHit(const Ray& ray, const Hit& hit, int depth, std::uint32_t pixelSeed, RayCounts& counts) const;
  Color sampleTexture(const Triangle& triangle, const Hit& hit) const;
  Tracer(const Scene& scene, const Scene& meshes, const Accel& accel, const ShadingGeometry& geometry,
         const RenderSettings& settings);

  const Scene& scene_;   // camera, lights, materials, depth
  const Scene& meshes_;  // triangles, normals, texture coordinates, texture
  const Accel& accel_;
  const ShadingGeometry& geometry_;
  RenderSettings settings_;
  int maxDepth_ = 0;
  CameraBasis basis_;
  glm::dvec3 eyeRelative_{0.0};
  std::vector<glm::dvec3> pointLightPositions_;
  std::vector<TriangularLightFrame> triangularLights_;
  bool useTexture_ = false;
};

}  // namespace rayview
