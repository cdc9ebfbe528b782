#pragma once
// A tiny software canvas for charts: rectangles, thick lines, markers and text (stb_easy_font's segment
// font), drawn supersampled and box-filtered down so edges are smooth. Coordinates are in output pixels,
// y down. Internal to the renderer library (used by plot.cpp).

#include <cstdint>
#include <string_view>

#include "rayview/image.h"

namespace rayview {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
};

enum class MarkerShape { Circle, Square, Triangle, Diamond, Star };
enum class TextAlign { Left, Centre, Right };

class PlotCanvas {
 public:
  PlotCanvas(int width, int height, Rgb background);

  void fillRect(double x0, double y0, double x1, double y1, Rgb colour);
  void line(double x0, double y0, double x1, double y1, double thickness, Rgb colour);
  void dashedLine(double x0, double y0, double x1, double y1, double thickness, double dash, Rgb colour);
  void marker(double x, double y, double radius, MarkerShape shape, Rgb colour);

  // Text with its top at `y`; `scale` 1 makes capitals about 7 pixels tall. ASCII only (others become '?').
  void text(double x, double y, std::string_view text, double scale, Rgb colour, TextAlign align = TextAlign::Left);
  // Reading upwards, centred on (x, y).
  void verticalText(double x, double y, std::string_view text, double scale, Rgb colour);
  static double textWidth(std::string_view text, double scale);

  Image finish() const;  // the box-filtered image

 private:
  template <class Inside>
  void fillWhere(double x0, double y0, double x1, double y1, Rgb colour, Inside inside);
  void textQuads(double x, double y, std::string_view text, double scale, Rgb colour, bool vertical);

  int width_, height_;
  Image fine_;  // supersampled
};

}  // namespace rayview
