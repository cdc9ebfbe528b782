#include "generated_scenes.h"

#include <cmath>

namespace rayview::bench {

Scene heightfieldScene(int triangles, int width, int height) {
  Scene scene;
  const int n = std::max(1, static_cast<int>(std::sqrt(triangles / 2.0)));  // quads per side
  scene.camera.position = {0.0, 6.0, 9.0};
  scene.camera.gaze = {0.0, -0.6, -1.0};
  scene.camera.width = width;
  scene.camera.height = height;
  scene.camera.top = 0.75 * height / width;
  scene.camera.bottom = -scene.camera.top;
  scene.camera.left = -0.75;
  scene.camera.right = 0.75;
  scene.maxRayDepth = 2;
  scene.background = Color(20.0f, 20.0f, 40.0f);
  scene.ambientLight = Color(25.0f);
  scene.pointLights.push_back({"sun", {3.0, 10.0, 4.0}, Color(12000.0f)});
  scene.triangularLights.push_back({"panel", {-3, 6, -1}, {-1, 6, 0}, {-3, 6, 1}, Color(3000.0f)});
  Material ground;
  ground.id = "ground";
  ground.ambient = Color(0.3f);
  ground.diffuse = Color(0.6f, 0.55f, 0.5f);
  ground.specular = Color(0.2f);
  ground.phongExponent = 10.0f;
  Material lake = ground;
  lake.id = "lake";
  lake.diffuse = Color(0.1f, 0.2f, 0.4f);
  lake.mirror = Color(0.5f);
  scene.materials = {ground, lake};

  const double size = 10.0;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = -size / 2 + size * i / n, z = -size / 2 + size * j / n;
      scene.vertices.push_back({x, 0.4 * std::sin(1.3 * x) * std::cos(0.9 * z) + 0.15 * std::sin(4.1 * x + 2.3 * z), z});
    }
  scene.meshes.push_back(Mesh{"terrain", 0, 0, 0});
  auto vertex = [&](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::uint32_t material = (i < n / 3 && j < n / 3) ? 1u : 0u;
      Triangle a, b;
      a.vertex[0] = vertex(i, j);
      a.vertex[1] = vertex(i, j + 1);
      a.vertex[2] = vertex(i + 1, j + 1);
      b.vertex[0] = vertex(i, j);
      b.vertex[1] = vertex(i + 1, j + 1);
      b.vertex[2] = vertex(i + 1, j);
      a.material = b.material = material;
      scene.triangles.push_back(a);
      scene.triangles.push_back(b);
    }
  scene.meshes[0].triangleCount = static_cast<std::uint32_t>(scene.triangles.size());
  return scene;
}

}  // namespace rayview::bench
