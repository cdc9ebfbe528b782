#pragma once
// Private: constructors of the traversal back-ends, chosen by buildAccel().

#include <cstddef>
#include <memory>
#include <string>

#include "rayview/accel.h"

namespace rayview {

// Embree's BVH layouts. Fast: the default flags, one triangle per leaf. Compact: Embree's COMPACT flag and up to
// two triangles per leaf: at 1e6 triangles the BVH is ~72 -> ~57 B per triangle and the build's peak lower by as
// much; rays through a random soup of triangles are 9-28 % slower, through a sphere or height field no slower
// (docs/PERFORMANCE.md, "Memory per triangle"). The answers are the same either way: every hit is the closest by
// the watertight test and the tie rule, whatever order the BVH visits the triangles in.
// Quick: the fast layout built at Embree's LOW quality, for a single render whose build outweighs it (fewer than
// kQuickBuildRaysPerTriangle camera rays a triangle): killeroo_2020's whole process 1.06x faster, car's (120 rays a
// triangle, kept Fast) 0.96x had it been Quick (docs/PERFORMANCE.md, "End to end and ceiling share").
// CompactQuick: the compact layout built at LOW quality, for one render of a scene past kCompactBvhTriangles with
// few rays a triangle: the 1M height field's build 1.6x faster, its render no slower, 114 -> 93 B/triangle.
enum class EmbreeLayout { Fast, Compact, Quick, CompactQuick };

// Scenes from this many triangles get the compact layout: there memory is what limits.
inline constexpr std::size_t kCompactBvhTriangles = 500'000;
inline constexpr std::size_t kQuickBuildRaysPerTriangle = 16;
// `pixels`: the one render's camera rays the BVH is built for; 0 when unknown or for many renders (the viewer).
EmbreeLayout embreeLayoutFor(std::size_t triangles, std::size_t pixels = 0);

// Every constructor takes the scene's cut-outs (null for none; buildAccel's contract).
std::unique_ptr<Accel> makeEmbreeAccel(const SceneGeometry& scene, const glm::dvec3& origin, EmbreeLayout layout,
                                       BuildProgress progress, void* progressUser, const CutOuts* cutOuts = nullptr);
// For tests: the fast layout on a device limited to one vector ISA ("avx2", "sse4.2"; Embree's `isa` setting).
// Embree's packet width follows the ISA (16 lanes with AVX-512, 8 with AVX2, 4 with SSE), so the callbacks get
// a 16-ray packet whole or in pieces: this builds each piece size on one machine.
std::unique_ptr<Accel> makeEmbreeAccelForIsa(const SceneGeometry& scene, const glm::dvec3& origin,
                                             const std::string& isa, const CutOuts* cutOuts = nullptr);
// rayview's packet BVH (packet_bvh_accel.cpp): Embree's answers for every ray within Embree's range, with no Embree.
// A big scene's build uses up to `buildThreads` threads (0: the hardware's); the BVH is the same for any number.
// Leaves hold one triangle, or up to `leafTriangles` (fewer nodes: less memory, slower rays; lean_memory.h).
std::unique_ptr<Accel> makePacketBvhAccel(const SceneGeometry& scene, const glm::dvec3& origin, unsigned buildThreads = 0,
                                          std::size_t leafTriangles = 1, const CutOuts* cutOuts = nullptr);
// prepareGeometry builds the packet BVH for AccelKind::Embree up to this many triangles: Embree's device, task
// scheduler and first build cost a process ~5 ms, more than its faster traversal saves a small scene's render
// (docs/PERFORMANCE.md, "The packet BVH for small scenes").
inline constexpr std::size_t kPacketBvhTriangles = 5000;
std::unique_ptr<Accel> makeReferenceAccel(const SceneGeometry& scene, const glm::dvec3& origin,
                                          BuildProgress progress, void* progressUser, const CutOuts* cutOuts = nullptr);

// `kind`, or the reference BVH when it is Embree and a vertex is beyond what Embree can represent (the
// geometry's part of embreeRangeProblem; buildAccel's check).
AccelKind accelWithinRange(const SceneGeometry& scene, AccelKind kind, const glm::dvec3& origin);

// buildAccel without its range check, for a caller that has made it (embreeRangeProblem covers it): the check
// reads every corner of every face, ~1 ms at 100 000 triangles, and a render made it three times.
// `pixels` as for embreeLayoutFor.
std::unique_ptr<Accel> buildCheckedAccel(const SceneGeometry& scene, AccelKind kind, const glm::dvec3& origin,
                                         BuildProgress progress, void* progressUser, std::size_t pixels = 0,
                                         const CutOuts* cutOuts = nullptr);

}  // namespace rayview
