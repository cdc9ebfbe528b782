#include "tile_plan.h"

#include <algorithm>
#include <cmath>

namespace rayview::cluster {

int clusterTileEdge(int width, int height, int ranks) {
  const double pixels = static_cast<double>(std::max(width, 1)) * std::max(height, 1);
  const double edge = std::sqrt(pixels / (static_cast<double>(std::max(ranks, 1)) * kTilesPerRank));
  const int rounded = static_cast<int>(edge / 4.0) * 4;
  return std::clamp(rounded, kMinTileEdge, kMaxTileEdge);
}

std::vector<Tile> clusterTiles(int width, int height, int ranks) {
  std::vector<Tile> tiles;
  if (width <= 0 || height <= 0) return tiles;
  const int edge = clusterTileEdge(width, height, ranks);
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

}  // namespace rayview::cluster
