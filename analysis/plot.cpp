#include "rayview/plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "rayview/plot_canvas.h"

namespace rayview {
namespace {

constexpr Rgb kWhite{255, 255, 255}, kBlack{0, 0, 0}, kInk{40, 40, 40}, kGrey{110, 110, 110};
constexpr Rgb kMajorGrid{215, 215, 215}, kMinorGrid{238, 238, 238};

// Okabe-Ito colours: distinct for colour-blind readers too. Each series is named by the knob's panel label
// (knobLabel), with the letter its points' labels start with.
struct SeriesStyle {
  TradeoffKnob knob;
  const char* letter;       // after the name in the legend: " (d)"
  const char* labelPrefix;  // before each point's setting: "d"
  Rgb colour;
  MarkerShape shape;
};
constexpr SeriesStyle kStyles[] = {
    {TradeoffKnob::Preview, "", "", {0, 114, 178}, MarkerShape::Circle},
    {TradeoffKnob::Depth, " (d)", "d", {213, 94, 0}, MarkerShape::Square},
    {TradeoffKnob::LightSamples, " (n)", "n=", {0, 158, 115}, MarkerShape::Triangle},
    {TradeoffKnob::Accel, "", "", {204, 121, 167}, MarkerShape::Diamond},
    {TradeoffKnob::PixelSamples, " (s)", "s=", {230, 159, 0}, MarkerShape::Star},
};
// A knob the table marks as measured that has no style above yet: the remaining Okabe-Ito colours in turn.
constexpr Rgb kMoreColours[] = {{86, 180, 233}, {240, 228, 66}, {0, 0, 0}};

// Every series of the measurement (tradeoffKnobs), in its order, each with its style.
std::vector<SeriesStyle> seriesStyles() {
  std::vector<SeriesStyle> series;
  std::size_t more = 0;
  for (const TradeoffKnob& knob : tradeoffKnobs()) {
    const auto style = std::find_if(std::begin(kStyles), std::end(kStyles),
                                    [&](const SeriesStyle& s) { return s.knob == knob; });
    if (style != std::end(kStyles)) series.push_back(*style);
    else series.push_back({knob, "", "", kMoreColours[more++ % std::size(kMoreColours)], MarkerShape::Circle});
  }
  return series;
}

constexpr double kTitleScale = 2.0, kAxisLabelScale = 1.6, kTickScale = 1.4, kPointLabelScale = 1.3;
constexpr double kMarkerRadius = 5.0;
constexpr double kFontCapHeight = 7.0;  // stb_easy_font capitals, at scale 1

std::string formatMs(double ms) {
  char text[32];
  if (ms >= 1000.0) std::snprintf(text, sizeof text, "%g s", ms / 1000.0);
  else std::snprintf(text, sizeof text, "%g ms", ms);
  return text;
}

std::string formatValue(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

// Where values land: log10 time across, log10 RMSE up, RMSE 0 in its own row below the log range.
struct Axes {
  double left = 0, right = 0, top = 0, bottom = 0;  // the plot rectangle
  double xLo = 0, xHi = 1;                           // decades of ms
  double yLo = -1, yHi = 0;                          // decades of RMSE
  double logBottom = 0;                              // y of 10^yLo
  double zeroRow = 0;                                // y of RMSE 0

  double x(double ms) const {
    const double l = std::log10(std::max(ms, 1e-6));
    return left + (l - xLo) / (xHi - xLo) * (right - left);
  }
  double y(double rmse) const {
    if (rmse <= 0.0) return zeroRow;
    const double l = std::clamp(std::log10(rmse), yLo, yHi);
    return logBottom - (l - yLo) / (yHi - yLo) * (logBottom - top);
  }
};

// Decades that enclose [lo, hi] with a little room at both ends.
void decadeRange(double lo, double hi, double& outLo, double& outHi) {
  outLo = std::floor(std::log10(lo) - 0.15);
  outHi = std::ceil(std::log10(hi) + 0.15);
  if (outHi <= outLo) outHi = outLo + 1.0;
}

// Label placement that avoids labels drawn before.
struct Box {
  double x0, y0, x1, y1;
  bool overlaps(const Box& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
};

class LabelPlacer {
 public:
  explicit LabelPlacer(const Axes& axes) : axes_(axes) {}
  // Returns false (and draws nothing) when every candidate spot is taken, unless `must`.
  bool place(PlotCanvas& canvas, double x, double y, const std::string& label, Rgb colour, bool must) {
    const double w = PlotCanvas::textWidth(label, kPointLabelScale), h = kFontCapHeight * kPointLabelScale;
    const double gap = kMarkerRadius + 3.0;
    const double candidates[][2] = {{x + gap, y - h / 2},       {x + gap, y - gap - h},     {x + gap, y + gap},
                                    {x - gap - w, y - h / 2},   {x - gap - w, y - gap - h}, {x - gap - w, y + gap},
                                    {x - w / 2, y - gap - h - 2}, {x - w / 2, y + gap + 2}};
    const Box* chosen = nullptr;
    Box box{};
    for (const auto& c : candidates) {
      box = {c[0] - 1, c[1] - 1, c[0] + w + 1, c[1] + h + 1};
      if (box.x0 < axes_.left || box.x1 > axes_.right || box.y0 < axes_.top || box.y1 > axes_.bottom) continue;
      if (std::none_of(placed_.begin(), placed_.end(), [&](const Box& p) { return p.overlaps(box); })) {
        chosen = &box;
        break;
      }
    }
    if (!chosen && !must) return false;
    if (!chosen) box = {candidates[0][0] - 1, candidates[0][1] - 1, candidates[0][0] + w + 1, candidates[0][1] + h + 1};
    canvas.fillRect(box.x0, box.y0, box.x1, box.y1, kWhite);  // a halo, for when it had to overlap
    canvas.text(box.x0 + 1, box.y0 + 1, label, kPointLabelScale, colour);
    placed_.push_back(box);
    return true;
  }
  void reserve(double x, double y, double radius) { placed_.push_back({x - radius, y - radius, x + radius, y + radius}); }
  // A drawn line, as small boxes along it (one box would cover a whole diagonal's rectangle).
  void reserveLine(double x0, double y0, double x1, double y1) {
    const int steps = std::max(1, static_cast<int>(std::hypot(x1 - x0, y1 - y0) / 3.0));
    for (int i = 0; i <= steps; ++i) reserve(x0 + (x1 - x0) * i / steps, y0 + (y1 - y0) * i / steps, 1.5);
  }

 private:
  const Axes& axes_;
  std::vector<Box> placed_;
};

const TradeoffPoint* findPoint(const TradeoffReport& report, TradeoffKnob knob, const char* label) {
  for (const TradeoffPoint& p : report.points)
    if (p.setting.knob == knob && (!label || p.setting.label == label)) return &p;
  return nullptr;
}

// measureTradeoff renders coinciding settings once: they share every figure.
bool sameRender(const TradeoffPoint& a, const TradeoffPoint& b) {
  return a.timeMs == b.timeMs && a.rays == b.rays && a.error.rmse == b.error.rmse;
}

std::vector<std::string> wrap(const std::string& text, double scale, double width) {
  std::vector<std::string> lines;
  std::string line;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find(' ', start);
    if (end == std::string::npos) end = text.size();
    const std::string word = text.substr(start, end - start);
    const std::string candidate = line.empty() ? word : line + " " + word;
    if (!line.empty() && PlotCanvas::textWidth(candidate, scale) > width) {
      lines.push_back(line);
      line = word;
    } else {
      line = candidate;
    }
    start = end + 1;
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

void drawGridAndTicks(PlotCanvas& canvas, const Axes& axes) {
  const bool fewXDecades = axes.xHi - axes.xLo <= 2.0, fewYDecades = axes.yHi - axes.yLo <= 2.0;
  for (double d = axes.xLo; d < axes.xHi + 0.5; d += 1.0)
    for (int m = 1; m <= 9; ++m) {
      const double ms = m * std::pow(10.0, d);
      if (std::log10(ms) > axes.xHi + 1e-9) break;
      const double x = axes.x(ms);
      const bool labelled = m == 1 || (fewXDecades && (m == 2 || m == 5));
      canvas.line(x, axes.top, x, axes.bottom, 1.0, labelled ? kMajorGrid : kMinorGrid);
      if (!labelled) continue;
      canvas.line(x, axes.bottom, x, axes.bottom + 5, 1.5, kInk);
      canvas.text(x, axes.bottom + 9, formatMs(ms), kTickScale, kInk, TextAlign::Centre);
    }
  for (double d = axes.yLo; d < axes.yHi + 0.5; d += 1.0)
    for (int m = 1; m <= 9; ++m) {
      const double v = m * std::pow(10.0, d);
      if (std::log10(v) > axes.yHi + 1e-9) break;
      const double y = axes.y(v);
      const bool labelled = m == 1 || (fewYDecades && (m == 2 || m == 5));
      canvas.line(axes.left, y, axes.right, y, 1.0, labelled ? kMajorGrid : kMinorGrid);
      if (!labelled) continue;
      canvas.line(axes.left - 5, y, axes.left, y, 1.5, kInk);
      canvas.text(axes.left - 8, y - kFontCapHeight * kTickScale / 2, formatValue(v), kTickScale, kInk, TextAlign::Right);
    }
  // The exact row, apart from the log range.
  const double separator = (axes.logBottom + axes.zeroRow) / 2.0;
  canvas.dashedLine(axes.left, separator, axes.right, separator, 1.0, 6.0, kGrey);
  canvas.line(axes.left, axes.zeroRow, axes.right, axes.zeroRow, 1.0, kMajorGrid);
  canvas.line(axes.left - 5, axes.zeroRow, axes.left, axes.zeroRow, 1.5, kInk);
  canvas.text(axes.left - 8, axes.zeroRow - kFontCapHeight * kTickScale / 2, "0 (exact)", kTickScale, kInk,
              TextAlign::Right);
}

void drawFrameAndTitles(PlotCanvas& canvas, const Axes& axes, const TradeoffReport& report, int height) {
  canvas.line(axes.left, axes.top, axes.left, axes.bottom, 1.5, kInk);
  canvas.line(axes.left, axes.bottom, axes.right, axes.bottom, 1.5, kInk);
  canvas.line(axes.right, axes.top, axes.right, axes.bottom, 1.0, kGrey);
  canvas.line(axes.left, axes.top, axes.right, axes.top, 1.0, kGrey);
  canvas.text(axes.left, 10, report.sceneName + ": error against render time", kTitleScale, kBlack);
  char subtitle[160];
  std::snprintf(subtitle, sizeof subtitle, "%dx%d pixels, %d thread%s; each knob varied alone; median time of repeated runs",
                report.width, report.height, report.threads, report.threads == 1 ? "" : "s");
  canvas.text(axes.left, 10 + kFontCapHeight * kTitleScale + 8, subtitle, kTickScale, kGrey);
  canvas.text((axes.left + axes.right) / 2, height - 22, "render time (log scale; BVH build not included)",
              kAxisLabelScale, kInk, TextAlign::Centre);
  canvas.verticalText(16, (axes.top + axes.bottom) / 2, "RMSE against the best image (0..255, log scale)",
                      kAxisLabelScale, kInk);
}

void drawLegend(PlotCanvas& canvas, const Axes& axes, const TradeoffReport& report, int width) {
  const double x = axes.right + 18, legendWidth = width - x - 10;
  double y = axes.top + 4;
  const double rowHeight = 22;
  const auto entry = [&](const std::string& name, Rgb colour, MarkerShape shape, bool withLine) {
    if (withLine) canvas.line(x, y + 5, x + 26, y + 5, 2.0, colour);
    canvas.marker(x + 13, y + 5, kMarkerRadius + 1.5, shape, kWhite);
    canvas.marker(x + 13, y + 5, kMarkerRadius, shape, colour);
    canvas.text(x + 34, y + 5 - kFontCapHeight * kTickScale / 2, name, kTickScale, kInk);
    y += rowHeight;
  };
  for (const SeriesStyle& s : seriesStyles())
    if (std::any_of(report.points.begin(), report.points.end(),
                    [&](const TradeoffPoint& p) { return p.setting.knob == s.knob; }))
      entry(std::string(knobLabel(s.knob)) + s.letter, s.colour, s.shape, true);
  entry(std::string(kBestImageLabel), kBlack, MarkerShape::Star, false);
  y += 6;
  std::vector<std::string> notes;
  if (!report.bestText.empty()) notes.push_back(std::string(kBestImageLabel) + ": " + report.bestText);
  if (!report.baselineText.empty()) notes.push_back("baseline: " + report.baselineText);
  notes.insert(notes.end(), report.notes.begin(), report.notes.end());
  for (const std::string& note : notes) {
    for (const std::string& line : wrap(note, 1.2, legendWidth)) {
      canvas.text(x, y, line, 1.2, kGrey);
      y += 13;
    }
    y += 5;
  }
}

}  // namespace

Image plotTradeoff(const TradeoffReport& report, int width, int height) {
  width = std::max(width, 400);
  height = std::max(height, 300);
  PlotCanvas canvas(width, height, kWhite);

  Axes axes;
  axes.left = 96;
  axes.right = width - 210;
  axes.top = 58;
  axes.bottom = height - 58;
  axes.zeroRow = axes.bottom - 14;
  axes.logBottom = axes.bottom - 40;

  double minMs = 1e300, maxMs = 0, minError = 1e300, maxError = 0;
  for (const TradeoffPoint& p : report.points) {
    minMs = std::min(minMs, std::max(p.timeMs, 1e-3));
    maxMs = std::max(maxMs, std::max(p.timeMs, 1e-3));
    if (p.error.rmse > 0.0) {
      minError = std::min(minError, p.error.rmse);
      maxError = std::max(maxError, p.error.rmse);
    }
  }
  if (report.points.empty()) minMs = 1, maxMs = 1000;
  if (maxError <= 0.0) minError = 0.1, maxError = 1.0;
  decadeRange(minMs, maxMs, axes.xLo, axes.xHi);
  decadeRange(minError, maxError, axes.yLo, axes.yHi);

  drawGridAndTicks(canvas, axes);
  drawFrameAndTitles(canvas, axes, report, height);
  drawLegend(canvas, axes, report, width);
  if (report.points.empty()) {
    canvas.text((axes.left + axes.right) / 2, (axes.top + axes.bottom) / 2,
                report.cancelled ? "measurement cancelled" : "nothing measured", kTitleScale, kGrey, TextAlign::Centre);
    return canvas.finish();
  }

  // Lines first, then markers over them, then labels where they fit (ends of each series always).
  LabelPlacer labels(axes);
  for (const SeriesStyle& s : seriesStyles()) {
    const TradeoffPoint* previous = nullptr;
    for (const TradeoffPoint& p : report.points) {
      if (p.setting.knob != s.knob) continue;
      if (previous) {
        const double x0 = axes.x(previous->timeMs), y0 = axes.y(previous->error.rmse);
        canvas.line(x0, y0, axes.x(p.timeMs), axes.y(p.error.rmse), 2.0, s.colour);
        labels.reserveLine(x0, y0, axes.x(p.timeMs), axes.y(p.error.rmse));
      }
      previous = &p;
    }
  }
  for (const TradeoffPoint& p : report.points) labels.reserve(axes.x(p.timeMs), axes.y(p.error.rmse), kMarkerRadius);
  const TradeoffPoint* best = findPoint(report, TradeoffKnob::BestImage, nullptr);
  const TradeoffPoint* baseline = findPoint(report, TradeoffKnob::Preview, "1");
  // Points that are the best image's or the baseline's render (every knob has one) get one black label.
  const auto sharedRender = [&](const TradeoffPoint& p) {
    return (best && sameRender(p, *best)) || (baseline && sameRender(p, *baseline));
  };
  if (best) labels.place(canvas, axes.x(best->timeMs), axes.y(0), std::string(kBestImageLabel), kBlack, true);
  if (baseline) labels.place(canvas, axes.x(baseline->timeMs), axes.y(baseline->error.rmse), "baseline", kBlack, true);
  for (const SeriesStyle& s : seriesStyles()) {
    std::vector<const TradeoffPoint*> series;
    for (const TradeoffPoint& p : report.points)
      if (p.setting.knob == s.knob) series.push_back(&p);
    for (const TradeoffPoint* p : series) {
      canvas.marker(axes.x(p->timeMs), axes.y(p->error.rmse), kMarkerRadius + 1.5, s.shape, kWhite);
      canvas.marker(axes.x(p->timeMs), axes.y(p->error.rmse), kMarkerRadius, s.shape, s.colour);
    }
    for (std::size_t i = 0; i < series.size(); ++i) {
      if (sharedRender(*series[i])) continue;
      const bool end = i == 0 || i + 1 == series.size();
      labels.place(canvas, axes.x(series[i]->timeMs), axes.y(series[i]->error.rmse),
                   s.labelPrefix + settingLabel(series[i]->setting), s.colour, end);
    }
  }
  if (best) {
    canvas.marker(axes.x(best->timeMs), axes.y(0), kMarkerRadius + 2.5, MarkerShape::Star, kWhite);
    canvas.marker(axes.x(best->timeMs), axes.y(0), kMarkerRadius + 1, MarkerShape::Star, kBlack);
  }
  return canvas.finish();
}

}  // namespace rayview
