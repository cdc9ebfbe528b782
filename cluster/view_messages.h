#pragma once
// The messages between the viewer on rank 0 and the ranks that trace its passes (docs/scale-out.md, "The viewer").

#include <cstdint>

namespace rayview::cluster {

enum ViewTag : int {
  kTagViewGeometry = 20,  // rank 0 -> worker: u64 geometry serial, then encodeGeometry's bytes
  kTagViewSnapshot = 21,  // rank 0 -> worker: ViewSnapshotHeader, then encodeSnapshot's bytes
  kTagViewTile = 22,      // rank 0 -> worker: ViewTileRequest
  kTagViewResult = 23,    // worker -> rank 0: ViewTileResultHeader, then 3 floats a pixel
  kTagViewProblem = 24,   // worker -> rank 0: why it cannot trace (text); rank 0 deals its tiles to the others
  kTagViewQuit = 25,      // rank 0 -> worker: one byte, 1 when a rank was lost; the window closed
  kTagViewBye = 26,       // worker -> rank 0: nothing; sent last, after every result
  // worker -> rank 0: nothing; while it builds or traces, and when it drops tiles of a replaced generation
  kTagViewAlive = 27,
};

struct ViewSnapshotHeader {
  std::uint64_t generation = 0;
  std::uint64_t geometry = 0;  // the serial of the geometry it is rendered with
};

// A tile of one pass: its grid rectangle (rayview/grid_render.h, gridTilePixels), the grid and the sample.
struct ViewTileRequest {
  std::uint64_t pass = 0;  // rank 0's serial of the pass: a result of an earlier pass is dropped
  std::uint64_t generation = 0;
  std::int32_t tile = 0;
  std::int32_t stride = 1, skipStride = 0, sample = -1;
  std::int32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

struct ViewTileResultHeader {
  std::uint64_t pass = 0;
  std::int32_t tile = 0;
  std::int32_t pixels = 0;
  double busyMs = 0.0;
  std::uint64_t camera = 0, shadow = 0, reflection = 0;
};

}  // namespace rayview::cluster
