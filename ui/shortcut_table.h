#pragma once
// Every key and mouse gesture the viewer answers, in one table: the key dispatch reads it to turn a key into a
// shortcut, and the help overlay (F1, ?) reads it to list them, so the two cannot disagree. No GL, no ImGui.

#include <optional>
#include <span>
#include <utility>

namespace rayview {

// What this frame's input asked for, besides navigation (NavigationInput fills it; the viewer applies it).
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
  bool toggleHelp = false;        // F1, ?: the list of these keys over the image
  bool closeHelp = false;         // Esc
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

// One row: the keys (GLFW_KEY_*, up to three, any of which; none for a mouse gesture or a held key, which
// NavigationInput handles itself and the table only lists), the modifiers (GLFW_MOD_CONTROL, GLFW_MOD_SHIFT) that
// must be down, those that may be either way, whether it works while a text field has the keyboard, how the help
// names it and what it does, and the action.
struct ShortcutRow {
  int keys[3] = {0, 0, 0};
  int mods = 0;
  int eitherMods = 0;
  bool inFields = false;
  const char* input = "";
  const char* does = "";
  void (*action)(Shortcuts&) = nullptr;
};

// The rows in the order the help lists them.
std::span<const ShortcutRow> shortcutTable();

// The row a key press with `mods` runs; nullptr when none (or when a text field has the keyboard and the row
// does not work there).
const ShortcutRow* matchShortcut(int key, int mods, bool fieldHasKeyboard);

}  // namespace rayview
