// The viewer's image view: fit, 1:1, zoom and pan (keys 0, 1, + and -, Ctrl+wheel, Ctrl+drag); the image
// drawn where the placement puts it, clipped to the image area, with a grid around the pixels at high zoom;
// and the readout of the pixel under the cursor (render and reference values).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <utility>
#include <cstdint>
#include <cstdio>
#include <string>

#include <imgui.h>

#include "numbered_file.h"
#include "rayview/view_camera.h"
#include "panels.h"
#include "viewer_app.h"
#include "window_capture.h"

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

}  // namespace

std::optional<std::pair<int, int>> ViewerApp::windowViewSize(const Layout& l) const {
  if (display_.imageView) return std::nullopt;
  // Framebuffer pixels: on a high-DPI screen, as many as the screen shows.
  return std::pair{std::max(1, static_cast<int>(std::lround(l.viewWidth * l.framebufferScale))),
                   std::max(1, static_cast<int>(std::lround(l.viewHeight * l.framebufferScale)))};
}

void ViewerApp::setImageView(bool imageView) {
  if (display_.imageView == imageView) return;
  display_.imageView = imageView;
  framesToDraw_ = kSettleFrames;
  // The next commit restarts the render at the view's resolution; saves and compares follow the file's image.
  std::printf("view %s\n", imageView ? "image" : "window");
  std::fflush(stdout);
}

bool ViewerApp::frameIsRendered() const {
  if (!haveFrame_ || !session_) return false;
  const Camera camera = session_->renderedCamera();
  return frame_.width == camera.width && frame_.height == camera.height;
}

void ViewerApp::applyImageView(const Shortcuts& shortcuts, const Layout& l) {
  if (shortcuts.toggleImageView) setImageView(!display_.imageView);
  if (!session_) return;
  const bool asked = shortcuts.imageFit || shortcuts.imageOneToOne || shortcuts.imageZoomBy != 1.0 ||
                     shortcuts.imageWheelZoomBy != 1.0 || shortcuts.imagePanX != 0.0 || shortcuts.imagePanY != 0.0;
  // Fit, 1:1, zoom and pan are of the file's image: from the window view they go to the image view.
  if (asked && !display_.imageView) setImageView(true);
  if (!display_.imageView) return;
  const ScreenRect view{l.viewX, l.viewY, l.viewWidth, l.viewHeight};
  const int w = session_->committedEdits().camera.width, h = session_->committedEdits().camera.height;
  const double scale = l.framebufferScale;
  // Another image size (another scene or resolution) starts fitted again.
  if (w != placedWidth_ || h != placedHeight_) {
    placedWidth_ = w;
    placedHeight_ = h;
    placement_.fit();
  }
  const double centreX = view.x + 0.5 * view.width, centreY = view.y + 0.5 * view.height;
  bool changed = false;
  if (shortcuts.imageFit) placement_.fit(), changed = true;
  if (shortcuts.imageOneToOne) placement_.zoomAt(1.0, centreX, centreY, view, w, h, scale), changed = true;
  if (shortcuts.imageZoomBy != 1.0) {
    placement_.zoomAt(placement_.zoom(view, w, h, scale) * shortcuts.imageZoomBy, centreX, centreY, view, w, h, scale);
    changed = true;
  }
  if (shortcuts.imageWheelZoomBy != 1.0) {
    placement_.zoomAt(placement_.zoom(view, w, h, scale) * shortcuts.imageWheelZoomBy, shortcuts.imageWheelAt.first,
                      shortcuts.imageWheelAt.second, view, w, h, scale);
    changed = true;
  }
  if (shortcuts.imagePanX != 0.0 || shortcuts.imagePanY != 0.0) {
    placement_.pan(shortcuts.imagePanX, shortcuts.imagePanY, view, w, h, scale);
    changed = true;
  }
  if (!changed) return;
  framesToDraw_ = kSettleFrames;
  // Tools driving the window (tests) follow the view on stdout.
  if (placement_.fitted()) std::printf("image view fit (zoom %.3f)\n", placement_.zoom(view, w, h, scale));
  else std::printf("image view zoom %.3f\n", placement_.zoom(view, w, h, scale));
  std::fflush(stdout);
}

void ViewerApp::drawImage(const ImageTexture& shown, const Layout& l) {
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  draw->PushClipRect(ImVec2(l.viewX, l.viewY), ImVec2(l.viewX + l.viewWidth, l.viewY + l.viewHeight), true);
  // The render's texture holds a coarse pass's samples, one texel per block; the reference and the difference
  // are at the image's size.
  const bool samples = &shown == &texture_;
  const ImVec2 uvMax = samples ? imageShareOfSamples(frame_) : ImVec2(1.0f, 1.0f);
  draw->AddImage(reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(shown.id())), ImVec2(l.imageX, l.imageY),
                 ImVec2(l.imageX + l.imageWidth, l.imageY + l.imageHeight), ImVec2(0.0f, 0.0f), uvMax);
  const int imageWidth = samples ? frame_.width : shown.width(), imageHeight = samples ? frame_.height : shown.height();
  // A grid around the pixels once each is big enough to see it, over the visible ones only.
  const double unitsPerPixel = l.imageWidth / imageWidth;
  if (unitsPerPixel * l.framebufferScale >= kPixelGridZoom) {
    const ImU32 colour = IM_COL32(128, 128, 128, 96);
    const int firstColumn = std::max(0, static_cast<int>(std::floor((l.viewX - l.imageX) / unitsPerPixel)));
    const int lastColumn =
        std::min(imageWidth, static_cast<int>(std::ceil((l.viewX + l.viewWidth - l.imageX) / unitsPerPixel)));
    const int firstRow = std::max(0, static_cast<int>(std::floor((l.viewY - l.imageY) / unitsPerPixel)));
    const int lastRow =
        std::min(imageHeight, static_cast<int>(std::ceil((l.viewY + l.viewHeight - l.imageY) / unitsPerPixel)));
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
  draw->PopClipRect();
}

void ViewerApp::drawPixelReadout(const Layout& l) {
  const ImGuiIO& io = ImGui::GetIO();
  std::optional<ImagePixel> pixel;
  const bool onView = io.MousePos.x >= l.viewX && io.MousePos.x < l.viewX + l.viewWidth && io.MousePos.y >= l.viewY &&
                      io.MousePos.y < l.viewY + l.viewHeight;
  if (frameIsRendered() && onView && !io.WantCaptureMouse)
    pixel = ImagePlacement::pixelAt({l.imageX, l.imageY, l.imageWidth, l.imageHeight}, frame_.width,
                                    frame_.height, screenPixelCentre(io.MousePos.x, l.framebufferScale),
                                    screenPixelCentre(io.MousePos.y, l.framebufferScale));
  if (!pixel) {
    readoutPixel_.reset();
    return;
  }
  std::string text = "pixel " + std::to_string(pixel->i) + ", " + std::to_string(pixel->j) + ": render " +
                     rgbText(frame_.image.pixel(pixel->i / std::max(frame_.stride, 1), pixel->j / std::max(frame_.stride, 1)));
  if (comparison_.comparable(frame_.width, frame_.height))
    text += ", reference " + rgbText(comparison_.reference().pixel(pixel->i, pixel->j));
  // In the window view, where the cursor is in the file's image (the pixel a reference or `pick I J` names).
  if (!display_.imageView) {
    const Camera& file = session_->committedEdits().camera;
    const ViewRect r = fileImageInWindowView(file, session_->renderedCamera());
    const double fi = std::floor((pixel->i + 0.5 - r.x) * file.width / r.width);
    const double fj = std::floor((pixel->j + 0.5 - r.y) * file.height / r.height);
    if (fi >= 0.0 && fi < file.width && fj >= 0.0 && fj < file.height)
      text += " (file pixel " + std::to_string(static_cast<int>(fi)) + ", " + std::to_string(static_cast<int>(fj)) + ")";
  }
  if (!frame_.final) text += " (preview pass)";
  drawReadoutOverlay(text, l.viewX + ImGui::GetStyle().WindowPadding.x,
                     l.viewY + l.viewHeight - ImGui::GetStyle().WindowPadding.y);
  if (printReadout_ && (readoutPixel_ != pixel || readoutText_ != text)) {
    std::printf("readout %s\n", text.c_str());
    std::fflush(stdout);
  }
  readoutPixel_ = pixel;
  readoutText_ = text;
}

void ViewerApp::writeViewSave(int framebufferWidth, int framebufferHeight, const Layout& l) {
  const std::string path = std::exchange(*pendingViewSave_, {});
  pendingViewSave_.reset();
  try {
    if (!haveFrame_) throw ImageIoError("no frame to save yet");
    // The image area in framebuffer pixels, rows from the top.
    const Image window = readWindowPixels(framebufferWidth, framebufferHeight);
    const int x0 = std::clamp(static_cast<int>(std::lround(l.viewX * l.framebufferScale)), 0, window.width);
    const int y0 = std::clamp(static_cast<int>(std::lround(l.viewY * l.framebufferScale)), 0, window.height);
    const int x1 = std::clamp(static_cast<int>(std::lround((l.viewX + l.viewWidth) * l.framebufferScale)), x0, window.width);
    const int y1 = std::clamp(static_cast<int>(std::lround((l.viewY + l.viewHeight) * l.framebufferScale)), y0, window.height);
    if (x1 <= x0 || y1 <= y0) throw ImageIoError("the image area is empty");
    Image view(x1 - x0, y1 - y0);
    for (int y = y0; y < y1; ++y)
      std::copy_n(window.pixel(x0, y), static_cast<std::size_t>(x1 - x0) * 3, view.pixel(0, y - y0));
    std::filesystem::path saved = path;
    if (path.empty()) saved = saveFrameNumbered(view, scenePath_, FrameSave::View);
    else writeImageFile(refusingInputs(path, scenePath_, session_ ? &session_->loaded() : nullptr), view);
    filePanel_.lastSaveFailed = false;
    filePanel_.lastSaved = "saved the view as seen: " + saved.string();
    captureOutcome_ = std::string();
    std::printf("saved view %s\n", saved.string().c_str());
    std::fflush(stdout);
  } catch (const ImageIoError& error) {
    filePanel_.lastSaved = std::string("view not saved: ") + error.what();
    filePanel_.lastSaveFailed = true;
    captureOutcome_ = error.what();
    std::fprintf(stderr, "rayview: view not saved: %s\n", error.what());
  }
}

}  // namespace rayview
