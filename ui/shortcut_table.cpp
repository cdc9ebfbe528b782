#include "shortcut_table.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace rayview {
namespace {

constexpr int kCtrl = GLFW_MOD_CONTROL;
constexpr int kShift = GLFW_MOD_SHIFT;
constexpr int kBoth = GLFW_MOD_CONTROL | GLFW_MOD_SHIFT;

// Keys that mean nothing to a text field (Ctrl shortcuts, function keys) work while one has the keyboard; the
// others would take a typed letter away from it.
constexpr ShortcutRow kRows[] = {
    {{GLFW_KEY_F1}, 0, kBoth, true, "F1 or ?", "show or hide this help",
     [](Shortcuts& s) { s.toggleHelp = true; }},
    {{GLFW_KEY_SLASH}, kShift, 0, false, "", "", [](Shortcuts& s) { s.toggleHelp = true; }},
    {{GLFW_KEY_ESCAPE}, 0, kBoth, false, "Esc", "hide this help", [](Shortcuts& s) { s.closeHelp = true; }},
    {{}, 0, 0, false, "left drag", "orbit around the pivot", nullptr},
    {{}, 0, 0, false, "middle drag, Shift+left drag", "pan", nullptr},
    {{}, 0, 0, false, "wheel", "dolly toward the point under the cursor", nullptr},
    {{}, 0, 0, false, "click", "pick the mesh and material under the cursor", nullptr},
    {{}, 0, 0, false, "double-click", "pick, and orbit about the point hit", nullptr},
    {{GLFW_KEY_HOME}, 0, kShift, false, "Home", "frame everything, ground planes too",
     [](Shortcuts& s) { s.frameAll = true; }},
    {{GLFW_KEY_F}, 0, kShift, false, "F", "frame the picked mesh, or the scene without its ground planes",
     [](Shortcuts& s) { s.frameScene = true; }},
    {{GLFW_KEY_R}, 0, kShift, false, "R", "reset to the file's camera", [](Shortcuts& s) { s.resetCamera = true; }},
    {{GLFW_KEY_Z}, kCtrl, 0, false, "Ctrl+Z", "undo", [](Shortcuts& s) { s.undo = true; }},
    {{GLFW_KEY_Z}, kBoth, 0, false, "Ctrl+Shift+Z, Ctrl+Y", "redo", [](Shortcuts& s) { s.redo = true; }},
    {{GLFW_KEY_Y}, kCtrl, kShift, false, "", "", [](Shortcuts& s) { s.redo = true; }},
    {{GLFW_KEY_E}, 0, 0, false, "E, Shift+E", "exposure up, down by half a stop (display only)",
     [](Shortcuts& s) { s.exposureSteps += 1; }},
    {{GLFW_KEY_E}, kShift, 0, false, "", "", [](Shortcuts& s) { s.exposureSteps -= 1; }},
    {{GLFW_KEY_V}, 0, kShift, false, "V", "the window view or the image view",
     [](Shortcuts& s) { s.toggleImageView = true; }},
    {{GLFW_KEY_1, GLFW_KEY_KP_1}, 0, kShift, false, "1", "image view: 1:1",
     [](Shortcuts& s) { s.imageOneToOne = true; }},
    {{GLFW_KEY_0, GLFW_KEY_KP_0}, 0, kShift, false, "0", "image view: fit", [](Shortcuts& s) { s.imageFit = true; }},
    {{GLFW_KEY_EQUAL, GLFW_KEY_KP_ADD}, 0, kShift, false, "+, -", "image view: zoom in, out by 2",
     [](Shortcuts& s) { s.imageZoomBy *= 2.0; }},
    {{GLFW_KEY_MINUS, GLFW_KEY_KP_SUBTRACT}, 0, kShift, false, "", "", [](Shortcuts& s) { s.imageZoomBy *= 0.5; }},
    {{}, 0, 0, false, "Ctrl+wheel, Ctrl+drag", "image view: zoom at the cursor, move the image", nullptr},
    {{}, 0, 0, false, "hold Space", "show the reference image instead of the render", nullptr},
    {{GLFW_KEY_D}, 0, kShift, false, "D", "the difference from the reference on or off",
     [](Shortcuts& s) { s.toggleDifference = true; }},
    {{GLFW_KEY_F11}, 0, kBoth, true, "F11", "fullscreen on or off", [](Shortcuts& s) { s.toggleFullscreen = true; }},
    {{GLFW_KEY_F9}, 0, kBoth, true, "F9", "hide or show the panels", [](Shortcuts& s) { s.togglePanels = true; }},
    {{GLFW_KEY_F5}, 0, kBoth, true, "F5", "load the scene again", [](Shortcuts& s) { s.reload = true; }},
    {{GLFW_KEY_S}, kCtrl, 0, true, "Ctrl+S", "save the file's image as a new numbered PNG",
     [](Shortcuts& s) { s.saveFrame = true; }},
    {{GLFW_KEY_S}, kBoth, 0, true, "Ctrl+Shift+S", "save the edited scene as a new numbered XML",
     [](Shortcuts& s) { s.saveScene = true; }},
    {{GLFW_KEY_O}, kCtrl, kShift, true, "Ctrl+O", "type a path to open", [](Shortcuts& s) { s.focusOpen = true; }},
    {{}, 0, 0, false, "drop a file", "open it", nullptr},
    {{GLFW_KEY_Q}, kCtrl, kShift, true, "Ctrl+Q", "quit (asks first when there are unsaved edits)",
     [](Shortcuts& s) { s.quit = true; }},
};

}  // namespace

std::span<const ShortcutRow> shortcutTable() { return kRows; }

const ShortcutRow* matchShortcut(int key, int mods, bool fieldHasKeyboard) {
  if (key == 0) return nullptr;
  for (const ShortcutRow& row : kRows) {
    if (!row.action || (fieldHasKeyboard && !row.inFields)) continue;
    // Alt and the others are not looked at; Ctrl and Shift must be as the row says, unless it takes either.
    if ((mods & kBoth & ~row.eitherMods) != row.mods) continue;
    for (const int k : row.keys)
      if (k == key) return &row;
  }
  return nullptr;
}

}  // namespace rayview
