#pragma once
// Undo and redo of the viewer's edits: a bounded stack of committed states (the scene's parameters and the
// render settings). One user gesture is one step: while a drag is in progress (the view, or a value held in a
// panel), the states it commits are folded into the step that the drag began. Pure logic, no ImGui.

#include <cstddef>
#include <deque>
#include <optional>

#include "rayview/render_settings.h"
#include "rayview/scene.h"

namespace rayview {

struct EditState {
  SceneParameters parameters;
  RenderSettings settings;
  bool operator==(const EditState&) const = default;
};

// Steps kept for undo; the oldest is dropped beyond this.
inline constexpr std::size_t kUndoLimit = 256;

class EditHistory {
 public:
  explicit EditHistory(EditState initial, std::size_t limit = kUndoLimit);

  // Called with each state that was committed (rendered, or a new traversal asked for). A state different from
  // the current one becomes a step, unless `inGesture` and the previous change belonged to the same gesture: then
  // it replaces the current state and the step still undoes to before the gesture. A new step clears redo.
  void record(const EditState& committed, bool inGesture);
  // The gesture is over (the button was released) even if its last frames changed nothing.
  void endGesture() { gestureOpen_ = false; }

  // The state to go back (or forward) to, which becomes the current one; nothing when there is none.
  std::optional<EditState> undo();
  std::optional<EditState> redo();

  const EditState& current() const { return current_; }
  std::size_t undoSteps() const { return undo_.size(); }
  std::size_t redoSteps() const { return redo_.size(); }

 private:
  std::size_t limit_;
  EditState current_;
  std::deque<EditState> undo_;  // oldest first
  std::deque<EditState> redo_;  // the next redo last
  bool gestureOpen_ = false;
};

}  // namespace rayview
