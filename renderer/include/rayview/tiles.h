#pragma once
// Splitting an image into tiles: at least 8 per thread, edge clamped to [1, 32], centre first.

#include <vector>

namespace rayview {

inline constexpr int kTilesPerThread = 8;
inline constexpr int kMaxTileSize = 32;

struct Tile {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // pixel rectangle [x0, x1) x [y0, y1)
};

int tileSizeFor(int width, int height, int threads);

// Tiles of `edge` pixels (the last row and column shorter) covering the image exactly once, ordered by distance of
// their centre from the image centre.
std::vector<Tile> tilesOfEdge(int width, int height, int edge);

// The same with tileSizeFor's edge: what a render on `threads` threads deals out.
std::vector<Tile> makeTiles(int width, int height, int threads);

}  // namespace rayview
