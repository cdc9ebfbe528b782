#pragma once
// Where the overlays over the image area go, so that none covers another, none runs over the panels or out of
// the window, and the stats keep clear of what the user is looking at (the picked mesh, the difference view)
// when there is room elsewhere. Pure arithmetic on rectangles in window units: no GL, no ImGui.

#include <optional>
#include <vector>

namespace rayview {

struct OverlayRect {
  float x = 0.0f, y = 0.0f, width = 0.0f, height = 0.0f;
  float right() const { return x + width; }
  float bottom() const { return y + height; }
  bool intersects(const OverlayRect& o) const {
    return x < o.right() && o.x < right() && y < o.bottom() && o.y < bottom();
  }
};

// An overlay's size as measured for its text on one line; `lineHeight` is what each further line adds when it
// is wrapped to a narrower width. 0 x 0: not shown.
struct OverlaySize {
  float width = 0.0f, height = 0.0f;
  float lineHeight = 0.0f;
  bool shown() const { return width > 0.0f && height > 0.0f; }
};

struct OverlayRequest {
  OverlayRect view;                 // the image area
  float margin = 8.0f;              // from the area's edges
  float gap = 4.0f;                 // between two overlays
  float topLeftHeight = 0.0f;       // the load error and progress, stacked at the top left (drawn by themselves)
  OverlaySize label;                // top right: what the image area shows (reference, difference)
  OverlaySize toast;                // top centre: the outcome of the last save
  OverlaySize progress;             // top centre, under the toast: a long full-resolution pass's progress
  OverlaySize statsBox, statsLine;  // bottom right: the stats as a box, and on one line
  bool oneLine = false;             // the stats on one line whatever the room (a small window, the user's choice)
  OverlaySize readout;              // bottom left: the pixel under the cursor
  // Where the stats should not go when they can go elsewhere: the picked mesh on screen, the difference view.
  std::vector<OverlayRect> keepClear;
};

struct OverlayPlacement {
  std::optional<OverlayRect> label, toast, progress, stats, readout;
  bool statsOneLine = false;  // the stats are drawn on one line (wrapped to stats->width when narrower)
};

OverlayPlacement placeOverlays(const OverlayRequest& request);

}  // namespace rayview
