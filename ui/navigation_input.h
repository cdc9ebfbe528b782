#pragma once
// Turns the window's mouse and keyboard events into camera navigation and shortcuts, after ImGui has
// had the first say: a press that ImGui wants never starts a drag, a key typed into a field is no shortcut.

#include <chrono>
#include <optional>
#include <vector>

#include "scene_session.h"
#include "window.h"

namespace rayview {

struct Shortcuts {
  bool frameScene = false;   // F
  bool resetCamera = false;  // R
  bool reload = false;       // F5
  bool saveFrame = false;    // Ctrl+S
  bool saveScene = false;    // Ctrl+Shift+S
  bool focusOpen = false;    // Ctrl+O
  bool quit = false;         // Ctrl+Q
  bool togglePanels = false; // F9
  bool undo = false;         // Ctrl+Z
  bool redo = false;         // Ctrl+Shift+Z, Ctrl+Y
  bool toggleDifference = false;  // D: the difference from the reference image
  bool toggleImageView = false;   // V: the image view (the file's image) or the window view (the area's pixels)
  bool frameAll = false;          // Home: frame every mesh, ground planes too
  bool toggleFullscreen = false;  // F11
  int exposureSteps = 0;          // E: +1, Shift+E: -1 (kExposureKeyStops each)
  // The wheel without Ctrl: dolly by these notches toward the scene point under the cursor (at dollyAt).
  double dollySteps = 0.0;
  std::pair<double, double> dollyAt{0.0, 0.0};
  // The image view (image_placement.h): 0 fits, 1 shows 1:1, + and - zoom by 2 at the view's centre,
  // Ctrl+wheel zooms at the cursor, Ctrl+drag moves the image.
  bool imageFit = false;
  bool imageOneToOne = false;
  double imageZoomBy = 1.0;                       // at the view's centre
  double imageWheelZoomBy = 1.0;                  // at imageWheelAt
  std::pair<double, double> imageWheelAt{0.0, 0.0};
  double imagePanX = 0.0, imagePanY = 0.0;        // window units
  // A left click on the image (pressed and released without moving more than kClickSlop pixels): where, in
  // window coordinates, and whether it completed a double-click.
  std::optional<std::pair<double, double>> click;
  bool doubleClick = false;
};

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
