#include "rayview/plot_canvas.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <stb_easy_font.h>

namespace rayview {
namespace {

constexpr int kSupersample = 3;  // 3x3 samples per output pixel
constexpr int kFontCapHeight = 7;

std::string printable(std::string_view text) {
  std::string s(text);
  for (char& c : s)
    if (c < 32 || c > 126) c = '?';
  return s;
}

double distanceToSegment(double px, double py, double x0, double y0, double x1, double y1) {
  const double dx = x1 - x0, dy = y1 - y0;
  const double lengthSquared = dx * dx + dy * dy;
  double t = lengthSquared > 0.0 ? ((px - x0) * dx + (py - y0) * dy) / lengthSquared : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(px - (x0 + t * dx), py - (y0 + t * dy));
}

}  // namespace

PlotCanvas::PlotCanvas(int width, int height, Rgb background)
    : width_(std::max(1, width)), height_(std::max(1, height)), fine_(width_ * kSupersample, height_ * kSupersample) {
  for (std::size_t i = 0; i < fine_.rgb.size(); i += 3) {
    fine_.rgb[i] = background.r;
    fine_.rgb[i + 1] = background.g;
    fine_.rgb[i + 2] = background.b;
  }
}

template <class Inside>
void PlotCanvas::fillWhere(double x0, double y0, double x1, double y1, Rgb colour, Inside inside) {
  // Fine pixels whose centres lie in the box and inside the shape.
  const int fx0 = std::max(0, static_cast<int>(std::floor(std::min(x0, x1) * kSupersample)));
  const int fy0 = std::max(0, static_cast<int>(std::floor(std::min(y0, y1) * kSupersample)));
  const int fx1 = std::min(fine_.width, static_cast<int>(std::ceil(std::max(x0, x1) * kSupersample)) + 1);
  const int fy1 = std::min(fine_.height, static_cast<int>(std::ceil(std::max(y0, y1) * kSupersample)) + 1);
  for (int fy = fy0; fy < fy1; ++fy)
    for (int fx = fx0; fx < fx1; ++fx) {
      const double px = (fx + 0.5) / kSupersample, py = (fy + 0.5) / kSupersample;
      if (!inside(px, py)) continue;
      std::uint8_t* p = fine_.pixel(fx, fy);
      p[0] = colour.r;
      p[1] = colour.g;
      p[2] = colour.b;
    }
}

void PlotCanvas::fillRect(double x0, double y0, double x1, double y1, Rgb colour) {
  const double left = std::min(x0, x1), right = std::max(x0, x1), top = std::min(y0, y1), bottom = std::max(y0, y1);
  fillWhere(left, top, right, bottom, colour,
            [&](double px, double py) { return px >= left && px < right && py >= top && py < bottom; });
}

void PlotCanvas::line(double x0, double y0, double x1, double y1, double thickness, Rgb colour) {
  const double r = thickness / 2.0;
  fillWhere(std::min(x0, x1) - r, std::min(y0, y1) - r, std::max(x0, x1) + r, std::max(y0, y1) + r, colour,
            [&](double px, double py) { return distanceToSegment(px, py, x0, y0, x1, y1) <= r; });
}

void PlotCanvas::dashedLine(double x0, double y0, double x1, double y1, double thickness, double dash, Rgb colour) {
  const double length = std::hypot(x1 - x0, y1 - y0);
  if (length <= 0.0 || dash <= 0.0) return;
  for (double s = 0.0; s < length; s += 2.0 * dash) {
    const double e = std::min(length, s + dash);
    line(x0 + (x1 - x0) * s / length, y0 + (y1 - y0) * s / length, x0 + (x1 - x0) * e / length,
         y0 + (y1 - y0) * e / length, thickness, colour);
  }
}

void PlotCanvas::marker(double x, double y, double radius, MarkerShape shape, Rgb colour) {
  const double r = radius;
  switch (shape) {
    case MarkerShape::Circle:
      fillWhere(x - r, y - r, x + r, y + r, colour, [&](double px, double py) { return std::hypot(px - x, py - y) <= r; });
      return;
    case MarkerShape::Square: {
      const double h = 0.85 * r;
      fillRect(x - h, y - h, x + h, y + h, colour);
      return;
    }
    case MarkerShape::Diamond: {
      const double h = 1.2 * r;
      fillWhere(x - h, y - h, x + h, y + h, colour,
                [&](double px, double py) { return std::abs(px - x) + std::abs(py - y) <= h; });
      return;
    }
    case MarkerShape::Triangle: {
      // Pointing up, centred on its centroid.
      const double h = 1.25 * r;
      const double ax = x, ay = y - h, bx = x - h * 0.866 * 1.15, by = y + h * 0.6, cx = x + h * 0.866 * 1.15, cy = by;
      const auto edge = [](double x0, double y0, double x1, double y1, double px, double py) {
        return (x1 - x0) * (py - y0) - (y1 - y0) * (px - x0);
      };
      fillWhere(bx, ay, cx, by, colour, [&](double px, double py) {
        const double e0 = edge(ax, ay, bx, by, px, py), e1 = edge(bx, by, cx, cy, px, py), e2 = edge(cx, cy, ax, ay, px, py);
        return (e0 <= 0 && e1 <= 0 && e2 <= 0) || (e0 >= 0 && e1 >= 0 && e2 >= 0);
      });
      return;
    }
    case MarkerShape::Star: {
      // Five points: the bound on the radius goes linearly from the tip to the notch between two tips.
      const double outer = 1.5 * r, inner = 0.6 * r, sector = 2.0 * std::numbers::pi / 5.0;
      fillWhere(x - outer, y - outer, x + outer, y + outer, colour, [&](double px, double py) {
        const double dx = px - x, dy = py - y;
        double angle = std::atan2(dx, -dy);  // 0 at the top tip
        angle = std::fmod(angle + 2.0 * std::numbers::pi, sector);
        const double fromTip = std::abs(angle - sector / 2.0) / (sector / 2.0);  // 1 at a tip, 0 at a notch
        return std::hypot(dx, dy) <= inner + (outer - inner) * fromTip;
      });
      return;
    }
  }
}

double PlotCanvas::textWidth(std::string_view text, double scale) {
  std::string s = printable(text);
  return stb_easy_font_width(s.data()) * scale;
}

void PlotCanvas::textQuads(double x, double y, std::string_view text, double scale, Rgb colour, bool vertical) {
  std::string s = printable(text);
  std::vector<float> vertices(s.size() * 400 + 64);  // stb_easy_font: ~270 bytes a character
  const int quads = stb_easy_font_print(0.0f, 0.0f, s.data(), nullptr, vertices.data(),
                                        static_cast<int>(vertices.size() * sizeof(float)));
  // Each quad is 4 vertices of (x, y, z, rgba) = 4 floats; vertices 0 and 2 are opposite corners.
  for (int q = 0; q < quads; ++q) {
    const float* v = &vertices[static_cast<std::size_t>(q) * 16];
    const double qx0 = v[0], qy0 = v[1], qx1 = v[8], qy1 = v[9];
    if (!vertical) fillRect(x + qx0 * scale, y + qy0 * scale, x + qx1 * scale, y + qy1 * scale, colour);
    else fillRect(x + qy0 * scale, y - qx0 * scale, x + qy1 * scale, y - qx1 * scale, colour);
  }
}

void PlotCanvas::text(double x, double y, std::string_view text, double scale, Rgb colour, TextAlign align) {
  const double w = textWidth(text, scale);
  const double left = align == TextAlign::Left ? x : (align == TextAlign::Centre ? x - w / 2.0 : x - w);
  textQuads(left, y, text, scale, colour, false);
}

void PlotCanvas::verticalText(double x, double y, std::string_view text, double scale, Rgb colour) {
  textQuads(x - kFontCapHeight * scale / 2.0, y + textWidth(text, scale) / 2.0, text, scale, colour, true);
}

Image PlotCanvas::finish() const {
  Image out(width_, height_);
  constexpr int kArea = kSupersample * kSupersample;
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x)
      for (int c = 0; c < 3; ++c) {
        int sum = 0;
        for (int sy = 0; sy < kSupersample; ++sy)
          for (int sx = 0; sx < kSupersample; ++sx)
            sum += fine_.pixel(x * kSupersample + sx, y * kSupersample + sy)[c];
        out.pixel(x, y)[c] = static_cast<std::uint8_t>((sum + kArea / 2) / kArea);
      }
  return out;
}

}  // namespace rayview
