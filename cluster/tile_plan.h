#pragma once
// The tiles a distributed render deals: square, their edge chosen from the image and the number of ranks.

#include <vector>

#include "rayview/tiles.h"

namespace rayview::cluster {

// About kTilesPerRank tiles a rank, so that dynamic dealing evens out unequal tiles; the edge a multiple of 4
// (whole 4x4 packets) within [kMinTileEdge, kMaxTileEdge]: big enough that a tile's pixels outweigh its message,
// small enough that one tile is a small part of a rank's share.
inline constexpr int kTilesPerRank = 24;
inline constexpr int kMinTileEdge = 16;
inline constexpr int kMaxTileEdge = 128;

int clusterTileEdge(int width, int height, int ranks);

// Tiles covering the image exactly once, centre first (the order the single-process render uses).
std::vector<Tile> clusterTiles(int width, int height, int ranks);

}  // namespace rayview::cluster
