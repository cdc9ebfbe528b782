#include "generated_scenes.h"

#include <cmath>
#include <random>
#include <vector>

namespace rayview::bench {

namespace {

// Camera, lights and the two materials every generated scene shares.
Scene baseScene(int width, int height) {
  Scene scene;
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
  scene.lights.of<PointLight>().push_back({"sun", {3.0, 10.0, 4.0}, Color(12000.0f)});
  scene.lights.of<TriangularLight>().push_back({"panel", {-3, 6, -1}, {-1, 6, 0}, {-3, 6, 1}, Color(3000.0f)});
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
  return scene;
}

}  // namespace

Scene heightfieldScene(int triangles, int width, int height) {
  Scene scene = baseScene(width, height);
  // Quads per side: at least `triangles` triangles (a series' "1e5" scene has 1e5 or a few hundred more).
  const int n = std::max(1, static_cast<int>(std::ceil(std::sqrt(triangles / 2.0))));

  const double size = 10.0;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = -size / 2 + size * i / n, z = -size / 2 + size * j / n;
      scene.vertices.push_back({x, 0.4 * std::sin(1.3 * x) * std::cos(0.9 * z) + 0.15 * std::sin(4.1 * x + 2.3 * z), z});
    }
  auto vertex = [&](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  SceneArray<Triangle> lake;  // a mesh of its own: the file format gives materials per mesh
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
      SceneArray<Triangle>& into = material == 1u ? lake : scene.triangles;
      into.push_back(a);
      into.push_back(b);
    }
  const auto terrain = static_cast<std::uint32_t>(scene.triangles.size());
  scene.triangles.insert(scene.triangles.end(), lake.begin(), lake.end());
  scene.meshes.push_back(Mesh{"terrain", 0, 0, terrain});
  scene.meshes.push_back(Mesh{"lake", 1, terrain, static_cast<std::uint32_t>(lake.size())});
  return scene;
}

}  // namespace rayview::bench

namespace rayview::bench {

Scene sphereScene(int triangles, int width, int height) {
  Scene scene = baseScene(width, height);
  scene.camera.position = {0.0, 1.0, 6.0};
  scene.camera.gaze = {0.0, -0.15, -1.0};
  // rings x segments quads, the pole rows as single triangles: 2 * rings * segments - 2 * segments triangles, at
  // least `triangles`.
  const int segments = std::max(3, static_cast<int>(std::sqrt(triangles)));
  const int rings = std::max(2, (triangles + 2 * segments - 1) / (2 * segments) + 1);
  const double radius = 2.0, pi = 3.14159265358979323846;
  for (int r = 0; r <= rings; ++r)
    for (int s = 0; s <= segments; ++s) {
      const double theta = pi * r / rings, phi = 2.0 * pi * s / segments;
      const glm::dvec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      scene.vertices.push_back(radius * n);
      scene.normals.push_back(glm::vec3(n));
    }
  auto vertex = [&](int r, int s) { return static_cast<std::uint32_t>(r * (segments + 1) + s); };
  auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    Triangle t;
    t.vertex[0] = a, t.vertex[1] = b, t.vertex[2] = c;
    FaceAttributes normals;
    for (int k = 0; k < 3; ++k) normals.normal[k] = static_cast<std::int32_t>(t.vertex[k]);
    scene.addFace(t, normals);
  };
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      // Counter-clockwise seen from outside.
      if (r != 0) add(vertex(r, s), vertex(r, s + 1), vertex(r + 1, s));
      if (r != rings - 1) add(vertex(r, s + 1), vertex(r + 1, s + 1), vertex(r + 1, s));
    }
  scene.meshes.push_back(Mesh{"sphere", 0, 0, static_cast<std::uint32_t>(scene.triangles.size())});
  return scene;
}

Scene soupScene(int triangles, int width, int height) {
  Scene scene = baseScene(width, height);
  scene.camera.position = {0.0, 2.0, 8.0};
  scene.camera.gaze = {0.0, -0.25, -1.0};
  std::mt19937_64 random(461);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  // Total area about 60 (the cube's faces are 96): a few layers deep wherever the cube is seen.
  const double edge = std::sqrt(60.0 / std::max(1, triangles) / 0.35);
  scene.vertices.reserve(3 * static_cast<std::size_t>(triangles));
  scene.triangles.reserve(static_cast<std::size_t>(triangles));
  const int mirrorsFrom = triangles - triangles / 7;
  for (int i = 0; i < triangles; ++i) {
    const glm::dvec3 centre(2.0 * unit(random), 2.0 * unit(random), 2.0 * unit(random));
    Triangle t;
    for (int k = 0; k < 3; ++k) {
      t.vertex[k] = static_cast<std::uint32_t>(scene.vertices.size());
      scene.vertices.push_back(centre + edge * glm::dvec3(unit(random), unit(random), unit(random)));
    }
    // The last seventh are mirrors, a mesh of their own (the file format gives materials per mesh).
    scene.triangles.push_back(t);
  }
  scene.meshes.push_back(Mesh{"soup", 0, 0, static_cast<std::uint32_t>(mirrorsFrom)});
  scene.meshes.push_back(Mesh{"mirrors", 1, static_cast<std::uint32_t>(mirrorsFrom),
                              static_cast<std::uint32_t>(triangles - mirrorsFrom)});
  return scene;
}

void roundCoordinates(Scene& scene) {
  for (glm::dvec3& v : scene.vertices)
    for (int k = 0; k < 3; ++k) v[k] = std::round(v[k] * 1e6) / 1e6;
}

}  // namespace rayview::bench
