// The parts of a distributed render that need no MPI: the tile plan, the pile that re-deals a lost rank's
// tiles, a tile's pixels against the whole frame's, the frames dealt whole or in tiles and put together, and the
// scene hash, and a batch's scenes as runs and as the orders rank 0 sends.
#include <gtest/gtest.h>

#include <set>

#include "rayview/frame_renderer.h"
#include "rayview/prepared_scene.h"
#include "rayview/scene_source.h"
#include "frame_units.h"
#include "scene_hash.h"
#include "scene_orders.h"
#include "unit_pile.h"
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

TEST(UnitPile, ALostRanksUnitsGoToTheOthersAndEveryUnitIsFinishedOnce) {
  UnitPile dealer(5);
  const auto a = dealer.take(1), b = dealer.take(1), c = dealer.take(2);
  ASSERT_TRUE(a && b && c);
  EXPECT_TRUE(dealer.finish(*a));
  EXPECT_EQ(dealer.reclaim(1), std::vector<std::size_t>{*b});
  // The reclaimed tile comes first, before the ones never dealt.
  EXPECT_EQ(dealer.next(), b);
  EXPECT_EQ(dealer.take(0), b);
  // A late result from the lost rank counts once; the other copy is not kept.
  EXPECT_TRUE(dealer.finish(*b));
  EXPECT_FALSE(dealer.finish(*b));
  std::set<std::size_t> rest;
  while (const auto t = dealer.take(0)) rest.insert(*t);
  EXPECT_EQ(rest.size(), 2u);
  for (std::size_t t : rest) dealer.finish(t);
  EXPECT_FALSE(dealer.allFinished());  // rank 2 still holds one
  EXPECT_TRUE(dealer.finish(*c));
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
  const auto geometry = prepareGeometry(scene, settings.accel, BvhBuild::Interactive);
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

TEST(FrameUnits, WholeFramesWhileAsManyRemainAsRanksThenTilesCoveringEachFrameOnce) {
  const int w = 100, h = 60;
  const std::vector<WorkUnit> units = frameUnits(7, w, h, 3);
  std::vector<std::vector<int>> covered(7, std::vector<int>(static_cast<std::size_t>(w) * h, 0));
  std::vector<int> whole(7, 0), tiles(7, 0);
  for (const WorkUnit& u : units) {
    const auto f = static_cast<std::size_t>(u.frame);
    ++(u.whole ? whole : tiles)[f];
    for (int y = u.tile.y0; y < u.tile.y1; ++y)
      for (int x = u.tile.x0; x < u.tile.x1; ++x) ++covered[f][static_cast<std::size_t>(y) * w + x];
  }
  for (int f = 0; f < 7; ++f) {
    // 7 frames on 3 ranks: frames 0-4 leave at least 3 to do, the last 2 are tiled.
    EXPECT_EQ(whole[static_cast<std::size_t>(f)], f < 5 ? 1 : 0) << f;
    EXPECT_EQ(tiles[static_cast<std::size_t>(f)], f < 5 ? 0 : static_cast<int>(clusterTiles(w, h, 3).size())) << f;
    for (int c : covered[static_cast<std::size_t>(f)]) ASSERT_EQ(c, 1);
  }
  for (const WorkUnit& u : frameUnits(4, w, h, 1)) EXPECT_TRUE(u.whole);  // one rank: no tiles
  for (const WorkUnit& u : frameUnits(1, w, h, 2)) EXPECT_FALSE(u.whole);  // one huge frame: all ranks on it
}

TEST(FrameAssembly, HandsEachFrameOnOnceWithEveryUnitInPlace) {
  const int w = 37, h = 21;
  const std::vector<WorkUnit> units = frameUnits(3, w, h, 2);  // frames 0, 1 whole, frame 2 in tiles
  std::vector<Image> written(3);
  std::vector<int> calls(3, 0);
  FrameAssembly assembly(units, [&](int frame, Image&& image) {
    ++calls[static_cast<std::size_t>(frame)];
    written[static_cast<std::size_t>(frame)] = std::move(image);
    return true;
  });
  // Each pixel's bytes say where it is and in which frame, so a misplaced unit shows.
  auto pixelsOf = [](const WorkUnit& u) {
    std::vector<std::uint8_t> rgb;
    for (int y = u.tile.y0; y < u.tile.y1; ++y)
      for (int x = u.tile.x0; x < u.tile.x1; ++x)
        rgb.insert(rgb.end(),
                   {static_cast<std::uint8_t>(x), static_cast<std::uint8_t>(y), static_cast<std::uint8_t>(u.frame)});
    return rgb;
  };
  for (std::size_t k = units.size(); k-- > 0;) {  // out of order, as results arrive
    const int frame = units[k].frame;
    EXPECT_EQ(calls[static_cast<std::size_t>(frame)], 0);
    assembly.place(k, pixelsOf(units[k]).data());
  }
  for (int f = 0; f < 3; ++f) {
    EXPECT_EQ(calls[static_cast<std::size_t>(f)], 1);
    const Image& image = written[static_cast<std::size_t>(f)];
    ASSERT_EQ(image.width, w);
    ASSERT_EQ(image.height, h);
    EXPECT_EQ(*image.pixel(36, 20), 36);
    EXPECT_EQ(image.pixel(36, 20)[1], 20);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) ASSERT_EQ(image.pixel(x, y)[2], f);
  }
  EXPECT_FALSE(assembly.failed());
}

TEST(FrameAssembly, AFrameNotWrittenFailsTheRun) {
  const std::vector<WorkUnit> units = frameUnits(2, 8, 8, 1);
  FrameAssembly assembly(units, [](int, Image&&) { return false; });
  const std::vector<std::uint8_t> rgb(8 * 8 * 3, 7);
  assembly.place(0, rgb.data());
  EXPECT_TRUE(assembly.failed());
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

TEST(SceneRuns, ConsecutiveFramesOfOneSceneAreOneRun) {
  const std::vector<FrameJob> frames = {{"a.xml", 0, 0, 0, "a.png"}, {"b.xml", 0, 0, 3, "b0.png"},
                                        {"b.xml", 0, 1, 3, "b1.png"}, {"c.xml", 0, 0, 0, "c.png"},
                                        {"c.xml", 2, 0, 0, "c2.png"}};
  const std::vector<SceneRun> runs = sceneRuns(frames);
  ASSERT_EQ(runs.size(), 4u) << "a file's other camera is a run of its own: it is opened with that camera";
  EXPECT_EQ(runs[0].first, 0u);
  EXPECT_EQ(runs[1].first, 1u);
  EXPECT_EQ(runs[1].end, 3u);
  EXPECT_EQ(runs[2].end, 4u);
  EXPECT_EQ(runs[3].end, 5u);
  EXPECT_TRUE(sceneRuns({}).empty());
}

TEST(SceneOrder, CarriesTheLoadedSceneExactlyAndRefusesMalformedBytes) {
  Scene scene = loadSceneOrDefault("", {}).scene;
  RenderSettings settings;
  settings.pixelSamples = 4;
  SceneOrder order;
  order.run = 7;
  order.scenePath = "scenes/x.xml";
  order.frames = {0, 0};
  order.geometry = encodeGeometry(scene.geometry(), scene.camera.position, settings.accel);
  order.parameters = encodeSnapshot(scene.parameters(), settings);
  const Bytes bytes = encodeSceneOrder(order);
  const SceneOrder back = decodeSceneOrder(bytes.data(), bytes.size());
  EXPECT_EQ(back.run, 7);
  EXPECT_EQ(back.scenePath, order.scenePath);
  EXPECT_EQ(back.frames, order.frames);
  // The scene a worker rebuilds from the order is rank 0's, hash for hash.
  Scene rebuilt;
  static_cast<SceneGeometry&>(rebuilt) = std::move(*decodeGeometry(back.geometry.data(), back.geometry.size()).geometry);
  const Snapshot snapshot = decodeSnapshot(back.parameters.data(), back.parameters.size());
  rebuilt.parameters() = snapshot.parameters;
  EXPECT_EQ(sceneHash(rebuilt), sceneHash(scene));
  EXPECT_EQ(snapshot.settings.pixelSamples, 4);
  for (std::size_t cut : {std::size_t{0}, std::size_t{3}, std::size_t{12}, bytes.size() / 2, bytes.size() - 1})
    EXPECT_THROW(decodeSceneOrder(bytes.data(), cut), CodecError) << cut;
  Bytes longer = bytes;
  longer.push_back(0);
  EXPECT_THROW(decodeSceneOrder(longer.data(), longer.size()), CodecError);
  Bytes foreign = bytes;
  foreign[0] ^= 1;
  EXPECT_THROW(decodeSceneOrder(foreign.data(), foreign.size()), CodecError);
}

}  // namespace
}  // namespace rayview::cluster
