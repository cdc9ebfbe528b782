#pragma once
// Where the viewer puts things this frame, in window coordinates: the panel column, the image area and the
// image as placed in it. Shared by the controllers that draw into the image area. No GL, no ImGui.

namespace rayview {

struct ViewerLayout {
  float panelWidth = 0.0f;
  float viewX = 0.0f, viewY = 0.0f, viewWidth = 0.0f, viewHeight = 0.0f;      // the area for the image
  float imageX = 0.0f, imageY = 0.0f, imageWidth = 0.0f, imageHeight = 0.0f;  // the image as placed
  float framebufferScale = 1.0f;

  bool inView(double x, double y) const { return x >= viewX && x < viewX + viewWidth && y >= viewY && y < viewY + viewHeight; }
};

}  // namespace rayview
