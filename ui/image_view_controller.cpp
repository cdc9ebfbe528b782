// The image view's placement, keys and mouse; drawing the image and its pixel grid; the pixel readout.
#include "image_view_controller.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include <imgui.h>

#include "panels.h"
#include "rayview/view_camera.h"

namespace rayview {
namespace {

std::string rgbText(const std::uint8_t* c) {
  return std::to_string(c[0]) + " " + std::to_string(c[1]) + " " + std::to_string(c[2]);
}

// The share of a pass's texture (one texel per block) that the image covers: the blocks at the right and
// bottom edges reach past it. Drawn over the image area with nearest filtering, the texels are the blocks.
ImVec2 imageShareOfSamples(const ProgressiveFrame& frame) {
  if (frame.image.width <= 0 || frame.image.height <= 0) return ImVec2(1.0f, 1.0f);
  return ImVec2(static_cast<float>(frame.width) / static_cast<float>(frame.image.width * frame.stride),
                static_cast<float>(frame.height) / static_cast<float>(frame.image.height * frame.stride));
}

// A grid around the pixels of an image of width x height drawn at l's image rectangle, over the visible ones only.
void drawPixelGrid(ImDrawList* draw, const ViewerLayout& l, int width, int height) {
  const double unitsPerPixel = l.imageWidth / width;
  const ImU32 colour = IM_COL32(128, 128, 128, 96);
  const int firstColumn = std::max(0, static_cast<int>(std::floor((l.viewX - l.imageX) / unitsPerPixel)));
  const int lastColumn = std::min(width, static_cast<int>(std::ceil((l.viewX + l.viewWidth - l.imageX) / unitsPerPixel)));
  const int firstRow = std::max(0, static_cast<int>(std::floor((l.viewY - l.imageY) / unitsPerPixel)));
  const int lastRow = std::min(height, static_cast<int>(std::ceil((l.viewY + l.viewHeight - l.imageY) / unitsPerPixel)));
  for (int i = firstColumn; i <= lastColumn; ++i) {
    const float x = l.imageX + static_cast<float>(i * unitsPerPixel);
    draw->AddLine(ImVec2(x, l.imageY + firstRow * unitsPerPixel), ImVec2(x, l.imageY + lastRow * unitsPerPixel), colour);
  }
  for (int j = firstRow; j <= lastRow; ++j) {
    const float y = l.imageY + static_cast<float>(j * unitsPerPixel);
    draw->AddLine(ImVec2(l.imageX + firstColumn * unitsPerPixel, y), ImVec2(l.imageX + lastColumn * unitsPerPixel, y),
                  colour);
  }
}

// " (file pixel I, J)" where window-view pixel (i, j) is inside the file's image, else "".
std::string filePixelText(int i, int j, const Camera& file, const Camera& rendered) {
  const ViewRect r = fileImageInWindowView(file, rendered);
  const double fi = std::floor((i + 0.5 - r.x) * file.width / r.width);
  const double fj = std::floor((j + 0.5 - r.y) * file.height / r.height);
  if (fi < 0.0 || fi >= file.width || fj < 0.0 || fj >= file.height) return {};
  return " (file pixel " + std::to_string(static_cast<int>(fi)) + ", " + std::to_string(static_cast<int>(fj)) + ")";
}

}  // namespace

ImageViewController::ImageViewController() : printReadout_(std::getenv("RAYVIEW_PRINT_READOUT") != nullptr) {}

bool ImageViewController::asked(const Shortcuts& s) {
  return s.imageFit || s.imageOneToOne || s.imageZoomBy != 1.0 || s.imageWheelZoomBy != 1.0 || s.imagePanX != 0.0 ||
         s.imagePanY != 0.0;
}

void ImageViewController::place(ViewerLayout& l, bool imageView, int width, int height) const {
  if (!imageView) {
    // The window view: the render is the image area's own pixels.
    l.imageX = l.viewX;
    l.imageY = l.viewY;
    l.imageWidth = l.viewWidth;
    l.imageHeight = l.viewHeight;
    return;
  }
  if (width <= 0 || height <= 0) return;
  // The file's image, fitted (aspect kept, square pixels) unless the user zoomed (image_placement.h). The image's
  // size, not the texture's: a coarse pass's texture holds one texel per block.
  const ScreenRect placed = placement_.place({l.viewX, l.viewY, l.viewWidth, l.viewHeight}, width, height, l.framebufferScale);
  l.imageX = static_cast<float>(placed.x);
  l.imageY = static_cast<float>(placed.y);
  l.imageWidth = static_cast<float>(placed.width);
  l.imageHeight = static_cast<float>(placed.height);
}

bool ImageViewController::applyShortcuts(const Shortcuts& s, const ViewerLayout& l, int w, int h) {
  const ScreenRect view{l.viewX, l.viewY, l.viewWidth, l.viewHeight};
  const double scale = l.framebufferScale;
  // Another image size (another scene or resolution) starts fitted again.
  if (w != placedWidth_ || h != placedHeight_) {
    placedWidth_ = w;
    placedHeight_ = h;
    placement_.fit();
  }
  const double centreX = view.x + 0.5 * view.width, centreY = view.y + 0.5 * view.height;
  if (!asked(s)) return false;
  if (s.imageFit) placement_.fit();
  if (s.imageOneToOne) placement_.zoomAt(1.0, centreX, centreY, view, w, h, scale);
  if (s.imageZoomBy != 1.0)
    placement_.zoomAt(placement_.zoom(view, w, h, scale) * s.imageZoomBy, centreX, centreY, view, w, h, scale);
  if (s.imageWheelZoomBy != 1.0)
    placement_.zoomAt(placement_.zoom(view, w, h, scale) * s.imageWheelZoomBy, s.imageWheelAt.first,
                      s.imageWheelAt.second, view, w, h, scale);
  if (s.imagePanX != 0.0 || s.imagePanY != 0.0) placement_.pan(s.imagePanX, s.imagePanY, view, w, h, scale);
  // Tools driving the window (tests) follow the view on stdout.
  if (placement_.fitted()) std::printf("image view fit (zoom %.3f)\n", placement_.zoom(view, w, h, scale));
  else std::printf("image view zoom %.3f\n", placement_.zoom(view, w, h, scale));
  std::fflush(stdout);
  return true;
}

void ImageViewController::drawImage(const ImageTexture& shown, const ViewerLayout& l,
                                    const ProgressiveFrame* samplesOf) const {
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  draw->PushClipRect(ImVec2(l.viewX, l.viewY), ImVec2(l.viewX + l.viewWidth, l.viewY + l.viewHeight), true);
  // The render's texture holds a coarse pass's samples, one texel per block; the reference and the difference
  // are at the image's size.
  const ImVec2 uvMax = samplesOf ? imageShareOfSamples(*samplesOf) : ImVec2(1.0f, 1.0f);
  draw->AddImage(reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(shown.id())), ImVec2(l.imageX, l.imageY),
                 ImVec2(l.imageX + l.imageWidth, l.imageY + l.imageHeight), ImVec2(0.0f, 0.0f), uvMax);
  const int width = samplesOf ? samplesOf->width : shown.width(), height = samplesOf ? samplesOf->height : shown.height();
  // A grid around the pixels once each is big enough to see it.
  if (l.imageWidth / width * l.framebufferScale >= kPixelGridZoom) drawPixelGrid(draw, l, width, height);
  draw->PopClipRect();
}

std::string ImageViewController::readout(const ViewerLayout& l, const ReadoutSource& src) {
  const ImGuiIO& io = ImGui::GetIO();
  const ProgressiveFrame& frame = src.frame;
  std::optional<ImagePixel> pixel;
  if (src.frameIsRendered && l.inView(io.MousePos.x, io.MousePos.y) && !io.WantCaptureMouse)
    pixel = ImagePlacement::pixelAt({l.imageX, l.imageY, l.imageWidth, l.imageHeight}, frame.width, frame.height,
                                    screenPixelCentre(io.MousePos.x, l.framebufferScale),
                                    screenPixelCentre(io.MousePos.y, l.framebufferScale));
  if (!pixel) {
    readoutPixel_.reset();
    return {};
  }
  const int stride = std::max(frame.stride, 1);
  std::string text = "pixel " + std::to_string(pixel->i) + ", " + std::to_string(pixel->j) +
                     ": render " + rgbText(frame.image.pixel(pixel->i / stride, pixel->j / stride));
  if (src.comparison.comparable(frame.width, frame.height))
    text += ", reference " + rgbText(src.comparison.reference().pixel(pixel->i, pixel->j));
  // In the window view, where the cursor is in the file's image (the pixel a reference or `pick I J` names).
  if (!src.imageView && src.file && src.rendered) text += filePixelText(pixel->i, pixel->j, *src.file, *src.rendered);
  if (!frame.final) text += " (preview pass)";
  if (printReadout_ && (readoutPixel_ != pixel || readoutText_ != text)) {
    std::printf("readout %s\n", text.c_str());
    std::fflush(stdout);
  }
  readoutPixel_ = pixel;
  readoutText_ = text;
  return text;
}

}  // namespace rayview
