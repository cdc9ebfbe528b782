// Placing the overlays over the image area: each in its corner, moved along the area's edge past the ones
// already placed, wrapped to the area's width when wider.
#include "overlay_layout.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace rayview {
namespace {

struct Placer {
  OverlayRect inner;  // the view less its margins
  float gap;
  std::vector<OverlayRect> taken;

  // `size` at the width it can have here: wrapped to the inner width when wider.
  OverlayRect sized(const OverlaySize& size) const {
    OverlayRect r{0.0f, 0.0f, std::min(size.width, inner.width), size.height};
    if (size.width > inner.width && inner.width > 0.0f) {
      const float lines = std::ceil(size.width / inner.width);
      r.height += (lines - 1.0f) * size.lineHeight;
    }
    return r;
  }

  // Moves `r` down (or up) past every rectangle it meets; nullopt when it then leaves the inner area.
  std::optional<OverlayRect> slide(OverlayRect r, bool down, const std::vector<OverlayRect>& avoid) const {
    for (std::size_t round = 0; round <= avoid.size(); ++round) {
      bool moved = false;
      for (const OverlayRect& o : avoid) {
        if (!r.intersects(o)) continue;
        r.y = down ? o.bottom() + gap : o.y - gap - r.height;
        moved = true;
      }
      if (!moved) break;
    }
    for (const OverlayRect& o : avoid)
      if (r.intersects(o)) return std::nullopt;
    if (r.y < inner.y || r.bottom() > inner.bottom() || r.x < inner.x || r.right() > inner.right()) return std::nullopt;
    return r;
  }

  enum class Corner { TopCentre, TopRight, BottomLeft, BottomRight };
  std::optional<OverlayRect> at(const OverlaySize& size, Corner corner, const std::vector<OverlayRect>& avoid) const {
    OverlayRect r = sized(size);
    const bool top = corner == Corner::TopCentre || corner == Corner::TopRight;
    r.y = top ? inner.y : inner.bottom() - r.height;
    if (corner == Corner::TopCentre) r.x = inner.x + 0.5f * (inner.width - r.width);
    else if (corner == Corner::BottomLeft) r.x = inner.x;
    else r.x = inner.right() - r.width;
    return slide(r, top, avoid);
  }

  std::vector<OverlayRect> with(const std::vector<OverlayRect>& extra) const {
    std::vector<OverlayRect> all = taken;
    all.insert(all.end(), extra.begin(), extra.end());
    return all;
  }
};

// The stats: a box where it fits and keeps clear, else one line; clear of keepClear if any place is, else
// anywhere free of the other overlays.
void placeStats(const OverlayRequest& q, Placer& p, OverlayPlacement& out) {
  struct Candidate {
    const OverlaySize* size;
    Placer::Corner corner;
    bool oneLine;
  };
  std::vector<Candidate> candidates;
  if (!q.oneLine && q.statsBox.shown() && q.statsBox.width <= p.inner.width) {
    candidates.push_back({&q.statsBox, Placer::Corner::BottomRight, false});
    candidates.push_back({&q.statsBox, Placer::Corner::TopRight, false});
  }
  candidates.push_back({&q.statsLine, Placer::Corner::BottomRight, true});
  candidates.push_back({&q.statsLine, Placer::Corner::TopRight, true});
  // Where nothing keeps clear of what the user looks at, cover as little of it as can be: one line first.
  std::vector<Candidate> smallestFirst = candidates;
  std::stable_partition(smallestFirst.begin(), smallestFirst.end(), [](const Candidate& c) { return c.oneLine; });
  for (const auto& [avoid, order] : {std::pair{p.with(q.keepClear), &candidates}, std::pair{p.taken, &smallestFirst}})
    for (const Candidate& c : *order)
      if (std::optional<OverlayRect> r = p.at(*c.size, c.corner, avoid)) {
        out.stats = r;
        out.statsOneLine = c.oneLine;
        p.taken.push_back(*r);
        return;
      }
}

}  // namespace

OverlayPlacement placeOverlays(const OverlayRequest& q) {
  Placer p{{q.view.x + q.margin, q.view.y + q.margin, std::max(0.0f, q.view.width - 2.0f * q.margin),
            std::max(0.0f, q.view.height - 2.0f * q.margin)},
           q.gap,
           {}};
  OverlayPlacement out;
  if (q.topLeftHeight > 0.0f) p.taken.push_back({p.inner.x, p.inner.y, p.inner.width, q.topLeftHeight});
  if (q.label.shown())
    if ((out.label = p.at(q.label, Placer::Corner::TopRight, p.taken))) p.taken.push_back(*out.label);
  if (q.toast.shown()) {
    out.toast = p.at(q.toast, Placer::Corner::TopCentre, p.taken);
    // Beside the load error there may be no room at the top: then at the bottom, above the others.
    if (!out.toast) out.toast = p.at(q.toast, Placer::Corner::BottomLeft, p.taken);
    if (out.toast) p.taken.push_back(*out.toast);
  }
  if (q.progress.shown())
    if ((out.progress = p.at(q.progress, Placer::Corner::TopCentre, p.taken))) p.taken.push_back(*out.progress);
  if (q.statsLine.shown()) placeStats(q, p, out);
  if (q.readout.shown())
    if ((out.readout = p.at(q.readout, Placer::Corner::BottomLeft, p.taken))) p.taken.push_back(*out.readout);
  return out;
}

}  // namespace rayview
