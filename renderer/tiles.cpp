#include "rayview/tiles.h"

#include <algorithm>
#include <cmath>

namespace rayview {

int tileSizeFor(int width, int height, int threads) {
  const double pixels = static_cast<double>(width) * height;
  const double wanted = static_cast<double>(std::max(threads, 1)) * kTilesPerThread;
  const int size = static_cast<int>(std::floor(std::sqrt(pixels / wanted)));
  return std::clamp(size, 1, kMaxTileSize);
}

std::vector<Tile> tilesOfEdge(int width, int height, int edge) {
  std::vector<Tile> tiles;
  if (width <= 0 || height <= 0 || edge <= 0) return tiles;
  for (int y = 0; y < height; y += edge)
    for (int x = 0; x < width; x += edge) tiles.push_back({x, y, std::min(x + edge, width), std::min(y + edge, height)});
  const double cx = width * 0.5, cy = height * 0.5;
  auto distance = [&](const Tile& t) {
    const double dx = (t.x0 + t.x1) * 0.5 - cx, dy = (t.y0 + t.y1) * 0.5 - cy;
    return dx * dx + dy * dy;
  };
  std::stable_sort(tiles.begin(), tiles.end(), [&](const Tile& a, const Tile& b) { return distance(a) < distance(b); });
  return tiles;
}

std::vector<Tile> makeTiles(int width, int height, int threads) {
  if (width <= 0 || height <= 0) return {};
  return tilesOfEdge(width, height, tileSizeFor(width, height, threads));
}

}  // namespace rayview
