#include "navigation_input.h"

#include <algorithm>
#include <cmath>
#include <utility>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace rayview {

void NavigationInput::handle(const std::vector<InputEvent>& events, bool imguiWantsMouse, bool imguiWantsKeyboard,
                             double viewHeight, double imageHeight, SceneSession* session, Shortcuts& shortcuts) {
  const double radiansPerPixel = kOrbitRadiansPerViewportHeight / std::max(viewHeight, 1.0);
  const double viewsPerPixel = 1.0 / std::max(imageHeight, 1.0);
  for (const InputEvent& e : events) {
    switch (e.kind) {
      case InputEvent::Kind::MouseButton:
        if (e.pressed && drag_ == Drag::None && !imguiWantsMouse && session) {
          const bool shift = (e.mods & GLFW_MOD_SHIFT) != 0;
          const bool control = (e.mods & GLFW_MOD_CONTROL) != 0;
          if (e.button == GLFW_MOUSE_BUTTON_LEFT) drag_ = control ? Drag::Image : shift ? Drag::Pan : Drag::Orbit;
          else if (e.button == GLFW_MOUSE_BUTTON_MIDDLE) drag_ = Drag::Pan;
          if (drag_ != Drag::None) {
            button_ = e.button;
            lastX_ = pressX_ = e.x;
            lastY_ = pressY_ = e.y;
            maybeClick_ = e.button == GLFW_MOUSE_BUTTON_LEFT && !shift && !control;
          }
        } else if (!e.pressed && e.button == button_) {
          drag_ = Drag::None;
          button_ = -1;
          if (std::exchange(maybeClick_, false)) {
            shortcuts.click = std::make_pair(e.x, e.y);
            const auto now = std::chrono::steady_clock::now();
            shortcuts.doubleClick = lastClickTime_ &&
                                    std::chrono::duration<double>(now - *lastClickTime_).count() < kDoubleClickSeconds &&
                                    std::abs(e.x - lastClickX_) <= kClickSlop && std::abs(e.y - lastClickY_) <= kClickSlop;
            // A third click starts a new pair.
            if (shortcuts.doubleClick) lastClickTime_.reset();
            else lastClickTime_ = now;
            lastClickX_ = e.x;
            lastClickY_ = e.y;
          }
        }
        break;
      case InputEvent::Kind::CursorMove: {
        cursorX_ = e.x;
        cursorY_ = e.y;
        if (drag_ == Drag::None || !session) break;
        if (std::abs(e.x - pressX_) > kClickSlop || std::abs(e.y - pressY_) > kClickSlop) maybeClick_ = false;
        const double dx = e.x - lastX_, dy = e.y - lastY_;
        lastX_ = e.x;
        lastY_ = e.y;
        // Grab the scene: it turns and slides with the cursor. Ctrl: grab the image instead.
        if (drag_ == Drag::Image) {
          shortcuts.imagePanX += dx;
          shortcuts.imagePanY += dy;
        } else if (drag_ == Drag::Orbit)
          session->navigate([&](OrbitCamera& o) { o.orbit(-dx * radiansPerPixel, dy * radiansPerPixel); });
        else
          session->navigate([&](OrbitCamera& o) { o.pan(-dx * viewsPerPixel, dy * viewsPerPixel); });
        break;
      }
      case InputEvent::Kind::Scroll:
        if (imguiWantsMouse || !session || e.y == 0.0) break;
        if ((e.mods & GLFW_MOD_CONTROL) != 0) {
          shortcuts.imageWheelZoomBy *= std::pow(kWheelZoomStep, e.y);
          shortcuts.imageWheelAt = {cursorX_, cursorY_};
        } else {
          // Toward the point under the cursor: the viewer casts the ray there (it knows the image's placement).
          shortcuts.dollySteps += e.y;
          shortcuts.dollyAt = {cursorX_, cursorY_};
        }
        break;
      case InputEvent::Kind::Key:
        // Keys typed right after Ctrl+O go to the path field, which takes the focus a frame later.
        handleKey(e, imguiWantsKeyboard || shortcuts.focusOpen, shortcuts);
        break;
    }
  }
}

void NavigationInput::handleKey(const InputEvent& e, bool imguiWantsKeyboard, Shortcuts& shortcuts) {
  const bool control = (e.mods & GLFW_MOD_CONTROL) != 0;
  if (e.key == GLFW_KEY_SPACE) {
    // A release always counts, even when a field took the focus while the key was down: never stuck flipped.
    if (!e.pressed) flipHeld_ = false;
    else if (!control && !imguiWantsKeyboard) flipHeld_ = true;
    return;
  }
  if (!e.pressed || e.repeat) return;
  // The table (shortcut_table.cpp) is what the help lists: a key does what its row says, nothing else.
  if (const ShortcutRow* row = matchShortcut(e.key, e.mods, imguiWantsKeyboard)) row->action(shortcuts);
}

}  // namespace rayview
