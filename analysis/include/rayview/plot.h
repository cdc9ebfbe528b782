#pragma once
// The error-against-time chart of a tradeoff report, rasterised to an Image (no GL): a log time axis, a log
// RMSE axis with a separate row for exact (0) results, one coloured series per knob with its settings
// labelled, the best image as a star, a legend. The viewer may show it as a texture; the bench writes it as PNG.

#include "rayview/image.h"
#include "rayview/tradeoff.h"

namespace rayview {

inline constexpr int kDefaultPlotWidth = 960;
inline constexpr int kDefaultPlotHeight = 600;

// Never throws for an empty or cancelled report: it then says so in the picture.
Image plotTradeoff(const TradeoffReport& report, int width = kDefaultPlotWidth, int height = kDefaultPlotHeight);

}  // namespace rayview
