// The parts of a distributed render that need no MPI: the tile plan, the dealer that re-deals a lost rank's
// tiles, a tile's pixels against the whole frame's, and the scene hash.
#include <gtest/gtest.h>

#include <set>

#include "rayview/frame_renderer.h"
#include "rayview/prepared_scene.h"
#include "rayview/scene_source.h"
#include "scene_hash.h"
#include "tile_dealer.h"
#include "tile_plan.h"
#include "tile_render.h"

namespace rayview::cluster {
namespace {

TEST(ClusterTiles, CoverTheImageOnceWithEdgesOfWholePackets) {
  for (int ranks : {1, 2, 4, 64})
    for (auto [w, h] : {std::pair{640, 480}, {17, 5}, {1000, 700}}) {
      const int edge = clusterTileEdge(w, h, ranks);
      EXPECT_EQ(edge % 4, 0);
      std::vector<int> covered(static_cast<std::size_t>(w) * h, 0);
      for (const Tile& t : clusterTiles(w, h, ranks))
        for (int y = t.y0; y < t.y1; ++y)
          for (int x = t.x0; x < t.x1; ++x) ++covered[static_cast<std::size_t>(y) * w + x];
      for (int c : covered) ASSERT_EQ(c, 1);
    }
  // More ranks, smaller tiles, down to the floor.
  EXPECT_GT(clusterTileEdge(1920, 1080, 1), clusterTileEdge(1920, 1080, 16));
  EXPECT_EQ(clusterTileEdge(1920, 1080, 10000), kMinTileEdge);
}

TEST(TileDealer, ALostRanksTilesGoToTheOthersAndEveryTileIsFinishedOnce) {
  TileDealer dealer(5);
  const auto a = dealer.take(1), b = dealer.take(1), c = dealer.take(2);
  ASSERT_TRUE(a && b && c);
  EXPECT_TRUE(dealer.finish(*a, 1));
  EXPECT_EQ(dealer.reclaim(1), std::vector<std::size_t>{*b});
  // The reclaimed tile comes first, before the ones never dealt.
  EXPECT_EQ(dealer.take(0), b);
  // A late result from the lost rank counts once; the other copy is not kept.
  EXPECT_TRUE(dealer.finish(*b, 1));
  EXPECT_FALSE(dealer.finish(*b, 0));
  std::set<std::size_t> rest;
  while (const auto t = dealer.take(0)) rest.insert(*t);
  EXPECT_EQ(rest.size(), 2u);
  for (std::size_t t : rest) dealer.finish(t, 0);
  EXPECT_FALSE(dealer.allFinished());  // rank 2 still holds one
  EXPECT_TRUE(dealer.finish(*c, 2));
  EXPECT_TRUE(dealer.allFinished());
  EXPECT_FALSE(dealer.takeOrWait(0));
}

TEST(ClusterTiles, TilesPutTogetherAreTheWholeFrameBitForBit) {
  Scene small = loadSceneOrDefault("", {}).scene;
  small.camera.width = 160;  // small: the test stays fast; the tiles are still uneven at the edges
  small.camera.height = 123;
  auto scene = std::make_shared<const Scene>(std::move(small));
  RenderSettings settings;
  settings.pixelSamples = 2;
  const auto geometry = prepareGeometry(scene, settings.accel);
  const Tracer tracer(scene->parameters(), *geometry, settings);
  ThreadPool pool(2);
  const int w = scene->camera.width, h = scene->camera.height;
  Image whole, pieced(w, h), tile;
  FrameStats stats;
  renderFrame(tracer, w, h, pool, whole, stats);
  RayCounts rays;
  for (const Tile& t : clusterTiles(w, h, 3)) {
    renderTile(tracer, t, pool, tile, rays);
    placeTile(t, tile.rgb.data(), pieced);
  }
  EXPECT_TRUE(whole.rgb == pieced.rgb);
  EXPECT_EQ(rays.total(), stats.rays.total());
}

TEST(SceneHash, SeesAnyChange) {
  Scene scene = loadSceneOrDefault("", {}).scene;
  const auto original = sceneHash(scene);
  EXPECT_EQ(sceneHash(scene), original);
  Scene moved = scene;
  moved.vertices[0].x += 1e-9;
  EXPECT_NE(sceneHash(moved), original);
  Scene lit = scene;
  lit.maxRayDepth += 1;
  EXPECT_NE(sceneHash(lit), original);
}

}  // namespace
}  // namespace rayview::cluster
