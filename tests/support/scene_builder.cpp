#include "support/scene_builder.h"

namespace rayview::testing {

Camera frontCamera(int size) {
  Camera camera;
  camera.width = camera.height = size;
  return camera;
}

Material plainMaterial(const std::string& id) {
  Material m;
  m.id = id;
  m.ambient = m.diffuse = Color(1.0f);
  return m;
}

void addTriangle(Scene& scene, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, std::uint32_t material) {
  const auto first = static_cast<std::uint32_t>(scene.vertices.size());
  scene.vertices.insert(scene.vertices.end(), {a, b, c});
  Triangle t;
  t.vertex[0] = first;
  t.vertex[1] = first + 1;
  t.vertex[2] = first + 2;
  scene.meshes.push_back(Mesh{std::string("m").append(std::to_string(scene.meshes.size())), material,
                              static_cast<std::uint32_t>(scene.triangles.size()), 1});
  scene.triangles.push_back(t);
}

void addQuadFacingZ(Scene& scene, double x0, double y0, double x1, double y1, double z, std::uint32_t material) {
  const auto first = static_cast<std::uint32_t>(scene.vertices.size());
  scene.vertices.insert(scene.vertices.end(), {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}});
  const auto mesh = static_cast<std::uint32_t>(scene.meshes.size());
  scene.meshes.push_back(Mesh{std::string("quad").append(std::to_string(mesh)), material, static_cast<std::uint32_t>(scene.triangles.size()), 2});
  for (auto [b, c] : {std::pair{1u, 2u}, std::pair{2u, 3u}}) {
    Triangle t;
    t.vertex[0] = first;
    t.vertex[1] = first + b;
    t.vertex[2] = first + c;
    scene.triangles.push_back(t);
  }
}

}  // namespace rayview::testing
