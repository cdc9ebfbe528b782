#pragma once
// Turns the window's mouse and keyboard events into camera navigation and shortcuts, after ImGui has
// had the first say: a press that ImGui wants never starts a drag, a key typed into a field is no shortcut.

#include <chrono>
#include <optional>
#include <vector>

#include "scene_session.h"
#include "shortcut_table.h"
#include "window.h"

namespace rayview {

// A press and release closer than this (window coordinates, per axis) is a click, not a drag.
inline constexpr double kClickSlop = 3.0;
// A second click this soon after the first, and as close, is a double-click.
inline constexpr double kDoubleClickSeconds = 0.4;
// One wheel notch with Ctrl zooms the image by this factor.
inline constexpr double kWheelZoomStep = 1.25;

class NavigationInput {
 public:
  // `viewHeight`: height in window coordinates of the area the image is shown in (orbit speed), and
  // `imageHeight` of the image itself (so that a pan moves the scene with the cursor).
  void handle(const std::vector<InputEvent>& events, bool imguiWantsMouse, bool imguiWantsKeyboard, double viewHeight,
              double imageHeight, SceneSession* session, Shortcuts& shortcuts);

  // Space is held: the reference image shows instead of the render (a key held, not a toggle).
  bool flipHeld() const { return flipHeld_; }
  // Keys stop counting as held (their release may go elsewhere, e.g. while a modal takes the input).
  void releaseKeys() { flipHeld_ = false; }

  // A navigation drag is in progress (the render holds its coarse level meanwhile).
  bool dragging() const { return drag_ != Drag::None; }
  void cancel() {
    drag_ = Drag::None;
    maybeClick_ = false;
  }

 private:
  enum class Drag { None, Orbit, Pan, Image };  // Image: Ctrl+drag moves the image, not the camera
  void handleKey(const InputEvent& e, bool imguiWantsKeyboard, Shortcuts& shortcuts);

  Drag drag_ = Drag::None;
  int button_ = -1;
  double lastX_ = 0.0, lastY_ = 0.0;
  double pressX_ = 0.0, pressY_ = 0.0;
  bool maybeClick_ = false;  // the left button went down on the image and has not moved far
  std::optional<std::chrono::steady_clock::time_point> lastClickTime_;
  double lastClickX_ = 0.0, lastClickY_ = 0.0;
  bool flipHeld_ = false;
  double cursorX_ = 0.0, cursorY_ = 0.0;  // the last cursor position seen, for the wheel's zoom
};

}  // namespace rayview
