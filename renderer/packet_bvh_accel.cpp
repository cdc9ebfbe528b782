// rayview's own BVH for small scenes: a binned-SAH binary tree of float boxes, traversed by packets of up to 16
// rays with the four-wide watertight test at the leaves. It answers exactly what the Embree back-end answers
// (the same float rays and boxes, the same watertight test and tie rule), without Embree's device, task scheduler
// and first build, which cost a small scene's process more than its render (docs/PERFORMANCE.md, "The packet
// BVH for small scenes").
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <new>
#include <optional>
#include <system_error>
#include <thread>
#include <vector>

#include "accel_backends.h"
#include "float_rays.h"
#include "float_steps.h"
#include "isa_clones.h"
#include "rayview/own_pages.h"
#include "watertight_lanes.h"
#include "watertight_triangle.h"

namespace rayview {
namespace {

using Float8 = float __attribute__((vector_size(32)));
using Int8 = std::int32_t __attribute__((vector_size(32)));

Float8 load8(const float* p) {
  Float8 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
Float8 splat8(float x) { return Float8{x, x, x, x, x, x, x, x}; }
Float8 min8(Float8 a, Float8 b) { return a < b ? a : b; }
Float8 max8(Float8 a, Float8 b) { return a < b ? b : a; }
unsigned bits8(Int8 m) {
#ifdef __AVX__
  return static_cast<unsigned>(__builtin_ia32_movmskps256(reinterpret_cast<Float8>(m)));
#elif defined(__SSE__)
  __m128 low, high;  // SSE's sign-bit mask takes four lanes: both halves, rather than a branch a lane
  std::memcpy(&low, &m, sizeof low);
  std::memcpy(&high, reinterpret_cast<const char*>(&m) + sizeof low, sizeof high);
  return static_cast<unsigned>(_mm_movemask_ps(low)) | static_cast<unsigned>(_mm_movemask_ps(high)) << 4;
#else
  unsigned b = 0;
  for (int j = 0; j < 8; ++j)
    if (m[j]) b |= 1u << j;
  return b;
#endif
}

struct Box {
  glm::vec3 lower{INFINITY}, upper{-INFINITY};
  void grow(const Box& b) {
    lower = glm::min(lower, b.lower);
    upper = glm::max(upper, b.upper);
  }
  void grow(const glm::vec3& p) {
    lower = glm::min(lower, p);
    upper = glm::max(upper, p);
  }
  float halfArea() const {
    const glm::vec3 e = upper - lower;
    return e.x < 0.0f ? 0.0f : e.x * e.y + e.y * e.z + e.z * e.x;
  }
};

// A node: a leaf's triangles are [first, first + count) in leaf order; an inner node's children are nodes first and
// first + 1, split along `axis`.
struct Node {
  float lower[3];
  std::uint32_t first;
  float upper[3];
  std::uint32_t countOrAxis;  // a leaf's count, or kInner | axis
};
constexpr std::uint32_t kInner = 0x80000000u;
static_assert(sizeof(Node) == 32 && alignof(Node) <= 64);

// The BVH's arrays in one block of cache lines, not zero-filled: the nodes, then the leaves' corners or their
// triangles' indices. Cache lines, so that a node's two children share one; one block, so that a small scene's arrays
// together reach kOwnPagesMinBytes and take pages of their own (rayview/own_pages.h): bunny's three, apart on the heap,
// were 930 KB first touched 4 KiB at a time.
struct alignas(64) CacheLine {
  std::byte bytes[64];
};
using Block = OwnPagesArray<CacheLine>;
Block allocateBlock(std::size_t bytes) { return Block((bytes + sizeof(CacheLine) - 1) / sizeof(CacheLine)); }

struct LeafTriangle {
  glm::dvec3 a, b, c;  // relative to the accel's origin, as the Embree back-end computes them per test
  std::uint32_t id;
};
static_assert(alignof(LeafTriangle) <= 64);

constexpr int kMaxDepth = 64;
constexpr int kBins = 16;
// Up to this many triangles with leaves of one, each leaf keeps its triangle's corners (80 bytes a triangle) instead
// of reading three indexed vertices and subtracting the origin at every visit. Beyond, and in the lean layout, the
// corners are computed per visit: memory per triangle matters more there (docs/PERFORMANCE.md).
constexpr std::size_t kKeptCornersTriangles = std::size_t{1} << 16;

// A triangle while the BVH builds: its box, its centroid as the box's own arithmetic gives it (one axis or all
// three), its index. Two layouts of the same values: CentroidKept, 40 bytes, for leaves of one triangle (builds ~8 %
// faster than computing the centroid where it is needed: bunny 2.5 against 2.7 ms); CentroidComputed, 28 bytes,
// for a lean scene's leaves of several, whose build must fit beside the scene (rayview/lean_memory.h).
struct CentroidComputed {
  Box box;
  std::uint32_t id;
  CentroidComputed(const Box& b, std::uint32_t i) : box(b), id(i) {}
  glm::vec3 centroid() const { return 0.5f * (box.lower + box.upper); }
  float centroid(int axis) const { return 0.5f * (box.lower[axis] + box.upper[axis]); }
};
struct CentroidKept {
  Box box;
  glm::vec3 center;
  std::uint32_t id;
  CentroidKept(const Box& b, std::uint32_t i) : box(b), center(0.5f * (b.lower + b.upper)), id(i) {}
  glm::vec3 centroid() const { return center; }
  float centroid(int axis) const { return center[axis]; }
};
static_assert(sizeof(CentroidComputed) == 28 && sizeof(CentroidKept) == 40);

// Builds into `nodes`, which has room for 2 * triangles + 2: the root at 1 and each pair of children (first,
// first + 1) from an even index (the array is 64-byte aligned, so the two boxes a visit tests share one cache line).
// Leaves of one triangle make 2 * triangles - 1 nodes; leaves of up to `leafMax` fewer. Written in place: a vector
// copied into the aligned array held 64 bytes a triangle twice at the build's peak.
//
// The nodes are taken pair by pair as the build goes, from the front of the array: with leaves of several triangles
// the array's tail is never touched, so never resident. The two subtrees under the top nodes of a big scene are
// built at once: the right one's nodes start where the left one's would end at the most (the descendants of a node
// over m triangles take at most 2 (m - 1) slots), so where every node lands depends on the triangles alone, not on
// the order or the thread its parts are built in.
template <class BuildTriangle>
class Builder {
 public:
  Builder(BigArray<BuildTriangle>& triangles, Node* nodes, unsigned threads, std::size_t leafMax)
      : triangles_(triangles), nodes_(nodes), leafMax_(leafMax) {
    if (threads == 0) threads = std::thread::hardware_concurrency();
    for (; threads > 1; threads /= 2) ++parallelDepth_;
  }

  void build() {
    std::size_t next = 2;
    split(1, 0, triangles_.size(), 0, next);
  }

 private:
  void makeLeaf(std::size_t node, std::size_t begin, std::size_t end, const Box& box) {
    Node& n = nodes_[node];
    store(n, box);
    n.first = static_cast<std::uint32_t>(begin);
    n.countOrAxis = static_cast<std::uint32_t>(end - begin);
  }
  static void store(Node& n, const Box& box) {
    for (int k = 0; k < 3; ++k) n.lower[k] = box.lower[k], n.upper[k] = box.upper[k];
  }

  // The bin of a centroid coordinate: 0 to bins - 1, whatever the float arithmetic gives (a NaN goes to bin 0).
  static int binOf(float value, float lo, float scale, int bins) {
    const float f = (value - lo) * scale;
    return f >= 1.0f ? (f < static_cast<float>(bins) ? static_cast<int>(f) : bins - 1) : 0;
  }

  // Where binned SAH splits triangles [begin, end) whose centroids span `centroids`: the axis (-1: none worth it),
  // the last bin of the left half, and the binning that decides which triangle goes where.
  struct SplitChoice {
    int axis = -1, bin = 0, binCount = 0;
    float lo[3] = {}, scale[3] = {};
  };
  SplitChoice chooseSplit(std::size_t begin, std::size_t end, const Box& centroids) const {
    // Binned SAH over the three axes, binned in one pass. An axis whose centroids span nothing a float bin width
    // can resolve (zero, or so small that bins / extent overflows) is not split along. Small nodes get fewer bins:
    // the sweep over the bins, not the binning, was most of the build (callgrind: ~2000 instructions a node).
    SplitChoice choice;
    const int binCount = choice.binCount = static_cast<int>(std::clamp<std::size_t>(2 * (end - begin), 4, kBins));
    float* const scale = choice.scale;
    float* const lo = choice.lo;
    for (int axis = 0; axis < 3; ++axis) {
      lo[axis] = centroids.lower[axis];
      const float extent = centroids.upper[axis] - lo[axis];
      scale[axis] = extent > 0.0f ? static_cast<float>(binCount) / extent : 0.0f;
      if (!std::isfinite(scale[axis])) scale[axis] = 0.0f;
    }
    Box bins[3][kBins];
    std::size_t counts[3][kBins] = {};
    for (std::size_t i = begin; i < end; ++i) {
      const BuildTriangle& t = triangles_[i];
      const glm::vec3 centroid = t.centroid();
      for (int axis = 0; axis < 3; ++axis) {
        const int b = binOf(centroid[axis], lo[axis], scale[axis], binCount);
        bins[axis][b].grow(t.box);
        ++counts[axis][b];
      }
    }
    float bestCost = INFINITY;
    for (int axis = 0; axis < 3; ++axis) {
      if (scale[axis] == 0.0f) continue;
      float rightArea[kBins];
      std::size_t rightCount[kBins];
      Box right;
      std::size_t n = 0;
      for (int b = binCount - 1; b > 0; --b) {
        right.grow(bins[axis][b]);
        n += counts[axis][b];
        rightArea[b] = right.halfArea();
        rightCount[b] = n;
      }
      Box left;
      n = 0;
      for (int b = 0; b < binCount - 1; ++b) {
        left.grow(bins[axis][b]);
        n += counts[axis][b];
        if (n == 0 || rightCount[b + 1] == 0) continue;
        const float cost = left.halfArea() * static_cast<float>(n) + rightArea[b + 1] * static_cast<float>(rightCount[b + 1]);
        if (cost < bestCost) bestCost = cost, choice.axis = axis, choice.bin = b;
      }
    }
    return choice;
  }

  // Builds the subtree of `node` over triangles [begin, end); its descendants take the slots from `next` on, which
  // it moves past them.
  void split(std::size_t node, std::size_t begin, std::size_t end, int depth, std::size_t& next) {
    Box box, centroids;
    for (std::size_t i = begin; i < end; ++i) {
      box.grow(triangles_[i].box);
      centroids.grow(triangles_[i].centroid());
    }
    const std::size_t count = end - begin;
    if (count <= leafMax_ || depth >= kMaxDepth - 2) return makeLeaf(node, begin, end, box);

    const SplitChoice choice = chooseSplit(begin, end, centroids);
    std::size_t middle;
    int axis = choice.axis;
    if (axis >= 0) {
      middle = static_cast<std::size_t>(
          std::partition(triangles_.begin() + static_cast<std::ptrdiff_t>(begin),
                         triangles_.begin() + static_cast<std::ptrdiff_t>(end),
                         [&](const BuildTriangle& t) {
                           return binOf(t.centroid(axis), choice.lo[axis], choice.scale[axis], choice.binCount) <=
                                  choice.bin;
                         }) -
          triangles_.begin());
    } else {
      // Every centroid in one point (or as good as): halves by index.
      axis = 0;
      middle = begin + count / 2;
    }
    if (middle == begin || middle == end) middle = begin + count / 2;

    const std::size_t left = next;
    next += 2;
    Node& n = nodes_[node];
    store(n, box);
    n.first = static_cast<std::uint32_t>(left);
    n.countOrAxis = kInner | static_cast<std::uint32_t>(axis);
    // The two halves touch disjoint triangles and slots. A thread is worth starting only for big halves.
    if (depth < parallelDepth_ && count >= kParallelMin) {
      // The right half's slots start where the left's would end at the most (leaves of one triangle).
      std::size_t rightNext = left + 2 * (middle - begin);
      const auto buildLeft = [&] { split(left, begin, middle, depth + 1, next); };
      const auto buildRight = [&] { split(left + 1, middle, end, depth + 1, rightNext); };
      std::thread right;
      try {
        right = std::thread(buildRight);
      } catch (const std::system_error&) {  // no thread to be had: this one builds both
      }
      buildLeft();
      if (right.joinable()) right.join();
      else buildRight();
      next = rightNext;
      return;
    }
    split(left, begin, middle, depth + 1, next);
    split(left + 1, middle, end, depth + 1, next);
  }

  static constexpr std::size_t kParallelMin = std::size_t{1} << 15;

  BigArray<BuildTriangle>& triangles_;
  Node* nodes_;
  std::size_t leafMax_;
  int parallelDepth_ = 0;  // nodes above this depth build their two halves at once: log2 of the hardware threads
};

// A packet's rays as the traversal reads them: float copies for the boxes (as the Embree back-end hands Embree),
// the watertight lanes in double for the triangles.
struct Packet {
  alignas(32) float org[3][kRayPacket];
  alignas(32) float inv[3][kRayPacket];
  alignas(32) float tNear[kRayPacket];
  alignas(32) float tFar[kRayPacket];
  WatertightLanes<kRayPacket> packed;
  const Ray* rays;  // lane k's ray is rays[k]
  // A block of four lanes' shared axis permutation, or -1 when its usable lanes do not share one: decided once
  // per packet, not at every leaf.
  int blockPermutation[kRayPacket / kWatertightWidth];
  TriangleHit hit[kRayPacket];
  std::uint32_t triangle[kRayPacket];
};

Packet& packetScratch() {
  thread_local Packet packet;
  return packet;
}

class PacketBvhAccel final : public Accel {
 public:
  PacketBvhAccel(const SceneGeometry& scene, const glm::dvec3& origin, unsigned buildThreads, std::size_t leafMax,
                 const CutOuts* cutOuts)
      : Accel(origin, scene), scene_(scene), cutOuts_(cutOuts) {
    if (leafMax > 1)
      build<CentroidComputed>(buildThreads, leafMax);
    else
      build<CentroidKept>(buildThreads, leafMax);
  }

  std::optional<Hit> closestHit(const Ray& ray) const override {
    std::optional<Hit> hit;
    closestHits(&ray, 1, &hit);
    return hit;
  }

  bool occluded(const Ray& ray) const override {
    bool answer = false;
    occludedMany(&ray, 1, &answer);
    return answer;
  }

  void closestHits(const Ray* rays, int count, std::optional<Hit>* hits) const override {
    Packet& p = packetScratch();
    const unsigned lanes = fill(p, rays, count, [&](int k) { hits[k] = closestHitByEveryTriangle(rays[k]); });
    for (int k = 0; k < count; ++k)
      if (lanes & (1u << k)) p.triangle[k] = kNoTriangle;
    if (lanes && nodes_)
      traverse(p, lanes, [&](int k, const LeafTriangle& t, const TriangleHit& hit, unsigned&) {
        if (p.triangle[k] != kNoTriangle && !replacesClosestHit(hit.t, t.id, p.hit[k].t, p.triangle[k])) return;
        p.hit[k] = hit;
        p.triangle[k] = t.id;
        p.packed.tFar[k] = std::min(p.rays[k].tFar, tieSearchLimit(hit.t));
        p.tFar[k] = widenedFar(p.packed.tFar[k]);
      });
    for (int k = 0; k < count; ++k) {
      if (!(lanes & (1u << k))) continue;
      if (p.triangle[k] == kNoTriangle) {
        hits[k].reset();
        continue;
      }
      Hit& hit = hits[k].emplace();
      hit.t = p.hit[k].t;
      hit.triangle = p.triangle[k];
      hit.b1 = p.hit[k].b1;
      hit.b2 = p.hit[k].b2;
    }
  }

  void occludedMany(const Ray* rays, int count, bool* answers) const override {
    Packet& p = packetScratch();
    const unsigned lanes = fill(p, rays, count, [&](int k) { answers[k] = occludedByAnyTriangle(rays[k]); });
    for (int k = 0; k < count; ++k)
      if (lanes & (1u << k)) answers[k] = false;
    if (lanes && nodes_)
      traverse(p, lanes, [&](int k, const LeafTriangle&, const TriangleHit&, unsigned& active) {
        answers[k] = true;
        active &= ~(1u << k);
      });
  }

  AccelKind kind() const override { return AccelKind::Packet; }

 private:
  // Builds the nodes and the leaves' triangle order, with `BuildTriangle` the build's layout of a triangle.
  template <class BuildTriangle>
  void build(unsigned buildThreads, std::size_t leafMax) {
    BigArray<BuildTriangle> triangles;
    triangles.reserve(scene_.triangles.size());
    for (std::uint32_t i = 0; i < scene_.triangles.size(); ++i) {
      // The Embree back-end's box for the triangle (float_rays.h).
      const FloatBox floatBox = floatBoxOf(cornersOf(scene_.vertices, scene_.triangles[i], origin()));
      Box box;
      box.lower = floatBox.lower, box.upper = floatBox.upper;
      // Embree skips a primitive whose box is not finite: so does this.
      bool finite = true;
      for (int k = 0; k < 3; ++k) finite &= std::isfinite(box.lower[k]) && std::isfinite(box.upper[k]);
      if (!finite) continue;
      triangles.emplace_back(box, i);
    }
    const std::size_t n = triangles.size();
    if (n == 0) return;
    const bool keepCorners = leafMax == 1 && n <= kKeptCornersTriangles;
    const std::size_t nodeBytes = (2 * n + 2) * sizeof(Node);  // a whole number of cache lines
    block_ = allocateBlock(nodeBytes + n * (keepCorners ? sizeof(LeafTriangle) : sizeof(std::uint32_t)));
    std::byte* const block = block_.data()->bytes;
    nodes_ = reinterpret_cast<Node*>(block);
    for (std::size_t i = 0; i < 2 * n + 2; ++i) ::new (static_cast<void*>(nodes_ + i)) Node;  // writes nothing
    Builder<BuildTriangle>(triangles, nodes_, buildThreads, leafMax).build();
    std::byte* const leaves = block + nodeBytes;
    if (keepCorners) {
      leafCorners_ = reinterpret_cast<LeafTriangle*>(leaves);
      for (std::size_t i = 0; i < n; ++i)
        ::new (static_cast<void*>(leafCorners_ + i)) LeafTriangle(corners(triangles[i].id));
    } else {
      leafTriangles_ = reinterpret_cast<std::uint32_t*>(leaves);
      for (std::size_t i = 0; i < n; ++i) leafTriangles_[i] = triangles[i].id;
    }
  }

  // Lanes k < count: the float-traversable ones set up in `p` (their bits returned), the others answered by
  // `without`. Four rays at a time, as the Embree back-end fills its packets (float_rays.h: the same prepared lanes,
  // the same float rays). Lanes without a ray keep what an earlier query left: the returned bits, which every box
  // test is masked with, leave them out.
  template <class Without>
  RAYVIEW_HOT static unsigned fill(Packet& p, const Ray* rays, int count, Without&& without) {
    unsigned lanes = 0;
    p.rays = rays;
    for (int first = 0; first < count; first += kWatertightWidth) {
      const FloatRays4 f = prepareFourRays(rays, first, count, p.packed);
      auto put = [&](float* to, Float4 v) { std::memcpy(to + first, &v, sizeof v); };
      const Float4 zero{}, tiny = splat4(1e-18f);
      for (int axis = 0; axis < 3; ++axis) {
        put(p.org[axis], f.origin[axis]);
        // A zero (or tiny) component would give 0 * inf in the slab test: a tiny one instead, as Embree does.
        const Float4 d = f.direction[axis];
        put(p.inv[axis], splat4(1.0f) / (((d < tiny) & (d > -tiny)) ? (d < zero ? -tiny : tiny) : d));
      }
      put(p.tNear, f.tNear);
      put(p.tFar, f.tFar);
      unsigned usable = 0, unanswered = 0;
      for (int j = 0; j < kWatertightWidth; ++j) {
        usable |= f.usable[j] ? 1u << j : 0u;
        unanswered |= f.inCount[j] && !f.usable[j] ? 1u << j : 0u;
      }
      lanes |= usable << first;
      for (; unanswered; unanswered &= unanswered - 1) without(first + __builtin_ctz(unanswered));
      int shared = -1;
      if (usable) {
        const int* permutation = p.packed.permutation + first;
        shared = permutation[__builtin_ctz(usable)];
        for (int j = 0; j < kWatertightWidth; ++j)
          if ((usable >> j) & 1u && permutation[j] != shared) shared = -1;
      }
      p.blockPermutation[first / kWatertightWidth] = shared;
    }
    return lanes;
  }

  // The lanes of `lanes` whose interval meets the node's box. Conservative: each slab's distances widened by
  // 2^-18 of themselves, far more than the float rounding of the distances (a few ulp).
  static unsigned boxLanes(const Packet& p, const Node& n, unsigned lanes) {
    constexpr float kSlack = 0x1p-18f;
    unsigned result = 0;
    for (int half = 0; half < 2; ++half) {
      if (!((lanes >> (8 * half)) & 0xFFu)) continue;
      const int at = 8 * half;
      Float8 near = load8(p.tNear + at), far = load8(p.tFar + at);
      for (int axis = 0; axis < 3; ++axis) {
        const Float8 o = load8(p.org[axis] + at), inv = load8(p.inv[axis] + at);
        const Float8 t0 = (splat8(n.lower[axis]) - o) * inv, t1 = (splat8(n.upper[axis]) - o) * inv;
        near = max8(near, min8(t0, t1));
        far = min8(far, max8(t0, t1));
      }
      // Widening each slab's distances by their own 2^-18 before the max / min is the same as widening the result
      // (x - |x| s and x + |x| s are increasing): once here. `near` is never negative (tNear is not), and a
      // negative `far` fails either way, so the widening is two products.
      result |= bits8(near * splat8(1.0f - kSlack) <= far * splat8(1.0f + kSlack)) << at;
    }
    return result & lanes;
  }

  // Every triangle whose box the packet's lanes meet, tested against those lanes; onHit(k, triangle, hit, active)
  // for each lane k that hits it within its interval (it may take lanes out of `active`).
  template <class OnHit>
  RAYVIEW_HOT void traverse(Packet& p, unsigned active, OnHit&& onHit) const {
    // Each entry: a node and the lanes that met its box when its parent was visited (both children's boxes are
    // tested then, from one cache line). A lane that has since found a closer hit may still be in the mask: its
    // tests are bounded by its current interval all the same.
    struct Entry {
      const Node* node;
      unsigned lanes;
    };
    Entry stack[2 * kMaxDepth];
    int top = 0;
    const Node& root = nodes_[1];
    if (const unsigned lanes = boxLanes(p, root, active)) stack[top++] = {&root, lanes};
    while (top > 0 && active) {
      const Entry entry = stack[--top];
      const Node& n = *entry.node;
      const unsigned lanes = entry.lanes & active;
      if (!lanes) continue;
      if (!(n.countOrAxis & kInner)) {
        if (leafCorners_) {
          for (std::uint32_t i = n.first; i < n.first + n.countOrAxis; ++i) {
            const LeafTriangle& t = leafCorners_[i];
            testLanes(p, t, lanes & active, [&](int k, const TriangleHit& hit) { keptHit(k, t, hit, active, onHit); });
          }
          continue;
        }
        for (std::uint32_t i = n.first; i < n.first + n.countOrAxis; ++i) {
          const LeafTriangle t = corners(leafTriangles_[i]);
          testLanes(p, t, lanes & active, [&](int k, const TriangleHit& hit) { keptHit(k, t, hit, active, onHit); });
        }
        continue;
      }
      const Node* children = &nodes_[n.first];
      const unsigned left = boxLanes(p, children[0], lanes), right = boxLanes(p, children[1], lanes);
      const int axis = static_cast<int>(n.countOrAxis & 3u);
      const bool backwards = p.inv[axis][__builtin_ctz(lanes)] < 0.0f;
      // The far child first onto the stack, so that the near one is visited first.
      const int nearSide = backwards ? 1 : 0;
      const unsigned nearLanes = backwards ? right : left, farLanes = backwards ? left : right;
      if (farLanes) stack[top++] = {&children[1 - nearSide], farLanes};
      if (nearLanes) stack[top++] = {&children[nearSide], nearLanes};
    }
  }

  // onHit for a hit that counts: not one a cut-out hides (one branch when the scene has none).
  template <class OnHit>
  void keptHit(int k, const LeafTriangle& t, const TriangleHit& hit, unsigned& active, OnHit& onHit) const {
    if (!cutOuts_ || !cutOuts_->hides(t.id, hit.b1, hit.b2)) onHit(k, t, hit, active);
  }

  // The lanes of `lanes` against the triangle, four at a time where four consecutive lanes from a multiple of four
  // share their axis permutation (as the Embree back-end's callbacks test them), else one at a time.
  template <class OnHit>
  static void testLanes(const Packet& p, const LeafTriangle& t, unsigned lanes, OnHit&& onHit) {
    while (lanes) {
      const int first = __builtin_ctz(lanes) & ~(kWatertightWidth - 1);
      const unsigned block = (lanes >> first) & 0xFu;
      lanes &= ~(0xFu << first);
      const int permutation = p.blockPermutation[first / kWatertightWidth];
      if (permutation >= 0 && (block & (block - 1)) != 0) {
        TriangleHits4 hits;
        for (unsigned hit = block & intersectWatertight4(p.packed, first, permutation, t.a, t.b, t.c, hits); hit;
             hit &= hit - 1) {
          const int j = __builtin_ctz(hit);
          if (t.id != p.rays[first + j].excludedTriangle) onHit(first + j, hits[j]);
        }
        continue;
      }
      for (unsigned rest = block; rest; rest &= rest - 1) {
        const int k = first + __builtin_ctz(rest);
        if (t.id == p.rays[k].excludedTriangle) continue;
        TriangleHit hit;
        if (intersectWatertight(p.packed.ray(k), t.a, t.b, t.c, p.rays[k].tNear, p.packed.tFar[k], hit)) onHit(k, hit);
      }
    }
  }

  // A triangle's corners relative to the origin, as the Embree back-end takes them (float_rays.h).
  LeafTriangle corners(std::uint32_t i) const {
    const TriangleCorners t = cornersOf(scene_.vertices, scene_.triangles[i], origin());
    return {t.a, t.b, t.c, i};
  }

  // A ray the float traversal turns away (the viewer's camera moved far from the build origin): every triangle, in
  // double, as the Embree back-end answers it.
  std::optional<Hit> closestHitByEveryTriangle(const Ray& ray) const {
    return rayview::closestHitByEveryTriangle(ray, static_cast<std::uint32_t>(scene_.triangles.size()), cutOuts_,
                                              [this](std::uint32_t i) { return corners(i); });
  }
  bool occludedByAnyTriangle(const Ray& ray) const {
    return rayview::occludedByAnyTriangle(ray, static_cast<std::uint32_t>(scene_.triangles.size()), cutOuts_,
                                          [this](std::uint32_t i) { return corners(i); });
  }

  Block block_;                             // holds the three below; empty without triangles
  Node* nodes_ = nullptr;                   // nodes_[1] is the root (nodes_[0] unused)
  LeafTriangle* leafCorners_ = nullptr;     // the triangles in leaf order with their corners (kKeptCornersTriangles),
  std::uint32_t* leafTriangles_ = nullptr;  // or their indices only
  const SceneGeometry& scene_;              // outlives the accel (buildAccel's contract)
  const CutOuts* cutOuts_;                  // null for a scene without cut-outs; outlives the accel too
};

}  // namespace

std::unique_ptr<Accel> makePacketBvhAccel(const SceneGeometry& scene, const glm::dvec3& origin, unsigned buildThreads,
                                          std::size_t leafTriangles, const CutOuts* cutOuts) {
  return std::make_unique<PacketBvhAccel>(scene, origin, buildThreads, std::max<std::size_t>(leafTriangles, 1),
                                          cutOuts);
}

}  // namespace rayview
