// Watertightness (SPEC section 6): camera rays aimed exactly at shared vertices, shared edges and shared
// quad diagonals of a flat mesh (a tessellated plane) and of closed meshes (cube, icosphere), from near and
// far (1 to 1e6 mesh sizes away) and from inside the closed meshes, never get through, on both back-ends.
//
// "Exactly": rays are float (Ray), so the mesh vertices are snapped to float-representable positions
// relative to the eye (the accelerator's origin) and both back-ends see exactly the same triangles; a ray
// toward a vertex then passes exactly through it. A ray toward a point on an edge is rounded to float; it
// is used when it passes within kMaxEdgeDeviation edge lengths of the point (far away, a float direction
// cannot resolve a point on a short edge, and only the vertices remain exact targets).
// A leak is a ray that misses, or, aimed from outside at a front-facing point of a closed mesh, first hits
// a triangle outside that point's neighbourhood (it went through the front surface and hit the back).
// Targets: every interior vertex, and on every interior edge its midpoint and kPointsPerEdge further points.
// Targets where the surface is seen nearly edge-on (|cos| < kMinCosine for a triangle around it) are
// silhouette points, which a ray may legitimately graze past, and are left out.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "rayview/accel.h"
#include "support/test_meshes.h"
#include "watertight_lanes.h"
#include "watertight_triangle.h"

namespace rayview {
namespace {

using testing::MeshTopology;
using testing::Placement;

constexpr int kPointsPerEdge = 4;
constexpr double kMinCosine = 0.1;
constexpr double kMaxEdgeDeviation = 0.01;
constexpr double kMeshSize = 0.5;  // half-size of the plane and the cube, radius of the icosphere
const double kDistances[] = {1, 10, 1e2, 1e3, 1e4, 1e5, 1e6};

// A point aimed at, and the triangles allowed to be hit first when it is seen from its front.
struct Target {
  glm::dvec3 point;
  std::vector<std::uint32_t> vertices;  // the vertex, or the edge's two vertices
  double tolerance = 0.0;               // how far the float ray may pass from the point
};

// Distance from `point` to the line through the origin along `direction`.
double distanceToRay(const glm::dvec3& point, const glm::dvec3& direction) {
  return glm::length(glm::cross(point, direction)) / glm::length(direction);
}

struct MeshCase {
  std::string name;
  std::function<void(Scene&, const Placement&)> add;
  bool closed;
};

struct Tally {
  long rays = 0, leaks = 0;
  long vertexRays = 0, vertexLeaks = 0;  // of which aimed at vertices
  long unresolvable = 0;                 // edge points a float ray cannot aim at
  void add(const Tally& o) {
    unresolvable += o.unresolvable;
    rays += o.rays;
    leaks += o.leaks;
    vertexRays += o.vertexRays;
    vertexLeaks += o.vertexLeaks;
  }
};

class Watertight : public ::testing::TestWithParam<AccelKind> {
 protected:
  void SetUp() override {
    if (availableAccel(GetParam()) != GetParam()) GTEST_SKIP() << "built without " << toString(GetParam());
  }

  // The mesh centred at `centre` as seen from an eye at the world origin, vertices snapped to float.
  void build(const MeshCase& mesh, const glm::dvec3& centre) {
    scene_ = Scene{};
    scene_.materials.push_back(Material{});
    mesh.add(scene_, Placement{centre, testing::genericRotation(), kMeshSize});
    for (glm::dvec3& v : scene_.vertices) v = glm::dvec3(glm::vec3(v));
    topology_ = testing::meshTopology(scene_, scene_.meshes[0]);
    targets_.clear();
    std::uint64_t state = 12345;
    auto uniform = [&] {  // a small LCG: deterministic points along the edges
      state = state * 6364136223846793005ULL + 1442695040888963407ULL;
      return 0.05 + 0.9 * static_cast<double>(state >> 11) * 0x1p-53;
    };
    for (std::uint32_t v = 0; v < scene_.vertices.size(); ++v)
      if (!topology_.vertexTriangles[v].empty() && !topology_.onBoundary[v]) targets_.push_back({scene_.vertices[v], {v}});
    for (const MeshTopology::Edge& e : topology_.edges) {
      if (e.triangles.size() != 2) continue;
      const glm::dvec3 &a = scene_.vertices[e.a], &b = scene_.vertices[e.b];
      const double tolerance = kMaxEdgeDeviation * glm::length(b - a);
      targets_.push_back({0.5 * (a + b), {e.a, e.b}, tolerance});
      for (int k = 0; k < kPointsPerEdge; ++k) targets_.push_back({a + uniform() * (b - a), {e.a, e.b}, tolerance});
    }
  }

  // Zero for a triangle that snapping to float made degenerate.
  glm::dvec3 normal(std::uint32_t triangle) const {
    const Triangle& t = scene_.triangles[triangle];
    const glm::dvec3& a = scene_.vertices[t.vertex[0]];
    const glm::dvec3 n = glm::cross(scene_.vertices[t.vertex[1]] - a, scene_.vertices[t.vertex[2]] - a);
    const double length = glm::length(n);
    return length > 0.0 ? n / length : glm::dvec3(0.0);
  }

  // +1: every triangle around the target faces the eye; -1: every one faces away; 0: a silhouette point.
  int facing(const Target& target, const glm::dvec3& eye) const {
    const glm::dvec3 toEye = glm::normalize(eye - target.point);
    int sign = 0;
    for (std::uint32_t v : target.vertices)
      for (std::uint32_t t : topology_.vertexTriangles[v]) {
        const double c = glm::dot(normal(t), toEye);
        const int s = c > kMinCosine ? 1 : c < -kMinCosine ? -1 : 0;
        if (s == 0 || (sign != 0 && s != sign)) return 0;
        sign = s;
      }
    return sign;
  }

  bool inNeighbourhood(std::uint32_t triangle, const Target& target) const {
    for (std::uint32_t v : target.vertices) {
      const auto& fan = topology_.vertexTriangles[v];
      if (std::find(fan.begin(), fan.end(), triangle) != fan.end()) return true;
    }
    return false;
  }

  // Aims one camera ray from the eye (the world origin) at every usable target.
  Tally shoot(bool closed, bool inside) {
    const glm::dvec3 eye(0.0);
    const std::unique_ptr<Accel> accel = buildAccel(scene_, GetParam(), eye);
    Tally tally;
    for (const Target& target : targets_) {
      const int side = inside ? 1 : facing(target, eye);
      if (side == 0) continue;
      const Ray ray{glm::vec3(0.0f), glm::vec3(target.point), 0.0f, INFINITY};
      if (distanceToRay(target.point, glm::dvec3(ray.direction)) > target.tolerance) {
        ++tally.unresolvable;
        continue;
      }
      ++tally.rays;
      const bool atVertex = target.vertices.size() == 1;
      tally.vertexRays += atVertex;
      const std::optional<Hit> hit = accel->closestHit(ray);
      const bool throughFront = hit && closed && !inside && side > 0 && !inNeighbourhood(hit->triangle, target);
      if (!hit || throughFront) {
        tally.vertexLeaks += atVertex;
        ++tally.leaks;
        if (++reported_ <= 3)
          ADD_FAILURE() << "leak at (" << target.point.x << ", " << target.point.y << ", " << target.point.z
                        << ") seen from the origin"
                        << (hit ? ": went through the front surface" : ": no hit");
      }
    }
    return tally;
  }

  Scene scene_;
  MeshTopology topology_;
  std::vector<Target> targets_;
  int reported_ = 0;  // leaks described one by one (the rest are counted)
};

std::vector<MeshCase> meshCases() {
  using namespace testing;
  return {{"plane", [](Scene& s, const Placement& p) { addTessellatedPlane(s, p, 12, 0); }, false},
          {"cube", [](Scene& s, const Placement& p) { addTessellatedCube(s, p, 4, 0); }, true},
          {"icosphere", [](Scene& s, const Placement& p) { addIcosphere(s, p, 3, 0); }, true}};
}

// View directions in the mesh's own frame: along the normal, oblique, grazing, from both sides.
std::vector<glm::dvec3> viewDirections() {
  std::vector<glm::dvec3> directions;
  for (double elevationDegrees : {90.0, 50.0, 15.0, 7.0, -60.0}) {
    const double e = elevationDegrees * std::numbers::pi / 180.0;
    directions.push_back(testing::genericRotation() * glm::dvec3(std::cos(e) * 0.8, std::cos(e) * 0.6, std::sin(e)));
  }
  directions.push_back(glm::normalize(glm::dvec3(1.0, 2.0, -0.5)));
  return directions;
}

TEST_P(Watertight, RaysAtSharedVerticesAndEdgesNeverLeak) {
  Tally total;
  for (const MeshCase& mesh : meshCases()) {
    for (double distance : kDistances) {
      Tally tally;
      for (const glm::dvec3& direction : viewDirections()) {
        build(mesh, -distance * direction);
        tally.add(shoot(mesh.closed, false));
      }
      std::printf("[ figures  ] %s %s, eye at %g: %ld rays, %ld leaks (%ld of %ld at vertices; %ld edge points "
                  "not resolvable in float)\n",
                  std::string(toString(GetParam())).c_str(), mesh.name.c_str(), distance, tally.rays, tally.leaks,
                  tally.vertexLeaks, tally.vertexRays, tally.unresolvable);
      total.add(tally);
    }
    if (mesh.closed) {
      Tally tally;
      for (const glm::dvec3& offset : {glm::dvec3(0.0), glm::dvec3(0.21, -0.13, 0.3), glm::dvec3(-0.4, 0.1, 0.05)}) {
        build(mesh, kMeshSize * offset);
        tally.add(shoot(true, true));
      }
      std::printf("[ figures  ] %s %s, eye inside: %ld rays, %ld leaks (%ld of %ld at vertices)\n",
                  std::string(toString(GetParam())).c_str(), mesh.name.c_str(), tally.rays, tally.leaks,
                  tally.vertexLeaks, tally.vertexRays);
      total.add(tally);
    }
  }
  std::printf("[ figures  ] %s: %ld rays at shared vertices and edges, %ld leaks (%ld of %ld at vertices)\n",
              std::string(toString(GetParam())).c_str(), total.rays, total.leaks, total.vertexLeaks, total.vertexRays);
  EXPECT_EQ(total.leaks, 0) << total.vertexLeaks << " of the leaks are rays through a vertex shared by the triangles "
                            "around it (see docs/numerics.md, Embree 3's robust mode misses some of them)";
  EXPECT_GT(total.rays, 100000);
}

// The test meshes themselves: closed meshes have every edge shared by exactly two triangles, facing out.
TEST(TestMeshes, ClosedMeshesAreClosedAndFaceOutward) {
  for (const MeshCase& mesh : meshCases()) {
    if (!mesh.closed) continue;
    Scene scene;
    const glm::dvec3 centre(3.7, -1.3, 2.1);
    mesh.add(scene, Placement{centre, testing::genericRotation(), kMeshSize});
    const MeshTopology topology = testing::meshTopology(scene, scene.meshes[0]);
    for (const MeshTopology::Edge& e : topology.edges) ASSERT_EQ(e.triangles.size(), 2u) << mesh.name;
    for (const Triangle& t : scene.triangles) {
      const glm::dvec3 &a = scene.vertices[t.vertex[0]], &b = scene.vertices[t.vertex[1]], &c = scene.vertices[t.vertex[2]];
      EXPECT_GT(glm::dot(glm::cross(b - a, c - a), (a + b + c) / 3.0 - centre), 0.0) << mesh.name;
    }
  }
}

// The tie rule's premise (watertight_triangle.h): a shared edge's function is exactly opposite in the two
// triangles, which holds only if the build rounds every product on its own (no fused multiply-add).
TEST(WatertightEdge, IsAntisymmetricBitForBit) {
  using watertight_detail::edgeFunction;
  using watertight_detail::Projected;
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-40, 40);
  auto value = [&] { return std::ldexp(mantissa(random), exponent(random)); };
  for (int i = 0; i < 200000; ++i) {
    const Projected p{value(), value()}, q{value(), value()};
    const double forward = edgeFunction(p, q), backward = edgeFunction(q, p);
    if (forward == 0.0) {
      ASSERT_EQ(backward, 0.0);
      continue;
    }
    ASSERT_EQ(std::bit_cast<std::uint64_t>(forward), std::bit_cast<std::uint64_t>(-backward))
        << p.x << " " << p.y << " " << q.x << " " << q.y;
  }
}

// The four-wide test (watertight_lanes.h) gives every lane exactly the scalar test's answer: the same hits, and
// t and barycentrics equal bit for bit. Rays in all six axis permutations at random triangles, at vertices and
// edges shared by two triangles (where the tie rule lives), in the plane of a triangle, at degenerate
// triangles, and with intervals ending exactly at the hit.
TEST(WatertightLanes, AgreeWithTheScalarTestBitForBit) {
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-20, 20);
  auto point = [&](double scale) { return glm::dvec3(unit(random), unit(random), unit(random)) * scale; };
  auto bits = [](double x) { return std::bit_cast<std::uint64_t>(x); };
  int hits = 0, compared = 0;
  for (int block = 0; block < 40000; ++block) {
    const double scale = std::ldexp(1.0, exponent(random));
    const glm::dvec3 centre = point(scale * 4.0);
    // Two triangles sharing the edge (v1, v2), listed in opposite orders as a mesh lists them; sometimes
    // a degenerate one.
    const glm::dvec3 v0 = centre + point(scale), v1 = centre + point(scale), v2 = centre + point(scale);
    glm::dvec3 w0 = centre + point(scale);
    const int kind = block % 8;
    if (kind == 6) w0 = v1 + 0.5 * (v2 - v1);  // collinear with the shared edge: area zero
    const glm::dvec3 corners[2][3] = {{v0, v1, v2}, {w0, v2, v1}};

    WatertightLanes<kWatertightWidth> lanes;
    WatertightRay prepared[kWatertightWidth];
    for (int j = 0; j < kWatertightWidth; ++j) {
      const glm::dvec3 origin = centre + point(scale * 8.0);
      glm::dvec3 target;
      switch ((kind + j) % 5) {
        case 0: target = v1; break;                                 // the shared vertex
        case 1: target = v1 + 0.5 * (v2 - v1); break;              // the shared edge
        case 2: target = v0 + 0.25 * (v1 - v0) + 0.25 * (v2 - v0); break;  // inside
        case 3: target = centre + point(scale); break;               // anywhere near
        default: target = v0 + (v1 - v0) * unit(random); break;      // the plane's edge line: grazing, in-plane
      }
      glm::dvec3 direction = target - origin;
      if (kind == 7 && j == 0) direction = (v1 - v0) * 3.0 + (v2 - v0);  // parallel to the plane
      if (!(glm::length(direction) > 0.0)) direction = glm::dvec3(0.0, 0.0, 1.0);
      prepared[j] = prepareWatertightRay(kind == 7 && j == 0 ? v0 : origin, direction);
      double tNear = 0.0, tFar = std::numeric_limits<double>::infinity();
      TriangleHit probe;
      if (j == 2 && intersectWatertight(prepared[j], v0, v1, v2, 0.0, tFar, probe)) tFar = probe.t;  // ends at it
      if (j == 3 && intersectWatertight(prepared[j], v0, v1, v2, 0.0, tFar, probe)) tNear = probe.t;  // starts at it
      if (kind == 5 && j == 1) tFar = 0.5;
      lanes.set(j, prepared[j], tNear, tFar);
    }
    for (const auto& corner : corners) {
      for (int j = 0; j < kWatertightWidth; ++j) {
        TriangleHit scalar;
        const bool scalarHit = intersectWatertight(prepared[j], corner[0], corner[1], corner[2], lanes.tNear[j],
                                                   lanes.tFar[j], scalar);
        TriangleHits4 wide;
        const unsigned mask = intersectWatertight4(lanes, 0, watertightPermutation(prepared[j]), corner[0], corner[1],
                                                   corner[2], wide);
        ++compared;
        ASSERT_EQ(scalarHit, (mask >> j & 1u) != 0) << "block " << block << " lane " << j;
        if (!scalarHit) continue;
        ++hits;
        ASSERT_EQ(bits(scalar.t), bits(wide[j].t)) << "block " << block << " lane " << j;
        ASSERT_EQ(bits(scalar.b1), bits(wide[j].b1)) << "block " << block << " lane " << j;
        ASSERT_EQ(bits(scalar.b2), bits(wide[j].b2)) << "block " << block << " lane " << j;
      }
    }
  }
  // The cases are not vacuous: a fair share of the lanes hit.
  EXPECT_GT(hits, compared / 5);
  EXPECT_LT(hits, compared);
}

// Four rays prepared at once (WatertightLanes::prepareFour, how a packet is filled) give each lane exactly what
// prepareWatertightRay and set() give it one at a time: the same permutation and the same shears, bit for bit.
// Directions with ties between the largest components (where the choice of axis lives), zero and negative-zero
// components, and every sign.
TEST(WatertightLanes, PreparedFourAtOnceAsOneAtATime) {
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> pick(0, 5);
  auto component = [&](double tie) {
    switch (pick(random)) {
      case 0: return tie;
      case 1: return -tie;
      case 2: return 0.0;
      case 3: return -0.0;
      default: return unit(random);
    }
  };
  auto bits = [](double x) { return std::bit_cast<std::uint64_t>(x); };
  int permutationsSeen = 0;
  for (int block = 0; block < 20000; ++block) {
    Double4 o[3], d[3], near, far;
    glm::dvec3 origins[kWatertightWidth], directions[kWatertightWidth];
    for (int j = 0; j < kWatertightWidth; ++j) {
      const double tie = unit(random);
      glm::dvec3 direction(component(tie), component(tie), component(tie));
      if (direction == glm::dvec3(0.0)) direction.z = tie != 0.0 ? tie : 1.0;
      origins[j] = glm::dvec3(unit(random), unit(random), unit(random)) * 100.0;
      directions[j] = direction;
      for (int axis = 0; axis < 3; ++axis) {
        o[axis][j] = origins[j][axis];
        d[axis][j] = direction[axis];
      }
      near[j] = unit(random) + 1.0;
      far[j] = near[j] + 2.0;
    }
    WatertightLanes<2 * kWatertightWidth> four, one;
    const int first = (block % 2) * kWatertightWidth;
    four.prepareFour(first, o, d, near, far);
    for (int j = 0; j < kWatertightWidth; ++j) {
      const WatertightRay scalar = prepareWatertightRay(origins[j], directions[j]);
      one.set(first + j, scalar, near[j], far[j]);
      const int k = first + j;
      ASSERT_EQ(four.permutation[k], one.permutation[k]) << "block " << block << " lane " << j;
      permutationsSeen |= 1 << four.permutation[k];
      for (int axis = 0; axis < 3; ++axis) ASSERT_EQ(bits(four.origin[axis][k]), bits(one.origin[axis][k]));
      ASSERT_EQ(bits(four.shearX[k]), bits(one.shearX[k])) << "block " << block << " lane " << j;
      ASSERT_EQ(bits(four.shearY[k]), bits(one.shearY[k])) << "block " << block << " lane " << j;
      ASSERT_EQ(bits(four.shearZ[k]), bits(one.shearZ[k])) << "block " << block << " lane " << j;
      ASSERT_EQ(bits(four.tNear[k]), bits(near[j]));
      ASSERT_EQ(bits(four.tFar[k]), bits(far[j]));
      // And the scalar test reads the lane back as prepareWatertightRay made it.
      const WatertightRay back = four.ray(k);
      ASSERT_EQ(back.kx, scalar.kx);
      ASSERT_EQ(back.ky, scalar.ky);
      ASSERT_EQ(back.kz, scalar.kz);
      ASSERT_EQ(bits(back.shearX), bits(scalar.shearX));
      ASSERT_EQ(bits(back.shearY), bits(scalar.shearY));
      ASSERT_EQ(bits(back.shearZ), bits(scalar.shearZ));
      ASSERT_EQ(back.origin, scalar.origin);
    }
  }
  EXPECT_EQ(permutationsSeen, 0b111111);  // all six permutations met
}

INSTANTIATE_TEST_SUITE_P(BothBackEnds, Watertight, ::testing::Values(AccelKind::Embree, AccelKind::Packet, AccelKind::Reference),
                         [](const auto& info) { return std::string(toString(info.param)); });

}  // namespace
}  // namespace rayview
