#pragma once
// The work of a run of frames of one scene as the ranks are dealt it, and rank 0's images of the frames in flight
// (docs/scale-out.md, "Frames"). No MPI.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <mutex>
#include <vector>

#include "rayview/image.h"
#include "rayview/tiles.h"

namespace rayview::cluster {

// One piece of work: a tile of frame `frame` (an index into the run), or the whole frame.
struct WorkUnit {
  int frame = 0;
  Tile tile;
  bool whole = false;  // the tile is the whole image: the frame is dealt to one rank
};

// A run of `frames` frames of width x height on `ranks` ranks: whole frames, in order, while at least as many
// frames remain (this one included) as there are ranks; each of the last ranks - 1 frames is split into the
// tiles clusterTiles gives, so that the run's end still keeps every rank busy. One rank: every frame whole.
std::vector<WorkUnit> frameUnits(int frames, int width, int height, int ranks);

// One image's tiles as the units of frame 0.
std::vector<WorkUnit> tileUnits(const std::vector<Tile>& tiles);

// Rank 0's images of the frames in flight: each unit's pixels are placed as they arrive (from any thread), and a
// frame is handed on once its last unit is in. A frame's image exists only between its first and last unit.
class FrameAssembly {
 public:
  // Called with a finished frame, one call at a time; false stops the job (its file could not be written).
  using Done = std::function<bool(int frame, Image&& image)>;
  FrameAssembly(const std::vector<WorkUnit>& units, Done done);

  // Places unit `unit`'s pixels (its tile's RGB rows); hands the frame on when it is the frame's last unit.
  void place(std::size_t unit, const std::uint8_t* rgb);
  bool failed() const;

 private:
  const std::vector<WorkUnit>& units_;
  Done done_;
  std::vector<std::size_t> missing_;  // per frame: units not placed yet
  std::vector<Tile> extent_;          // per frame: the image's size, from its units
  std::vector<Image> images_;
  bool failed_ = false;
  mutable std::mutex mutex_;
  std::mutex doneMutex_;  // one frame handed on at a time, outside mutex_: other units keep being placed
};

}  // namespace rayview::cluster
