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
  if (width <= 0 || height <= 0) return {};
  return tilesOfEdge(width, height, clusterTileEdge(width, height, ranks));
}

}  // namespace rayview::cluster
