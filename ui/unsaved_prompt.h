#pragma once
// Unsaved edits: opening another scene or quitting from the window asks first, in a modal (Save, Discard,
// Cancel; keys S or Enter, D, Esc or C). Scripts' open and quit do not ask: they discard.

#include <optional>
#include <string>
#include <vector>

#include "window.h"

namespace rayview {

class UnsavedPrompt {
 public:
  enum class Action { Quit, Open };
  enum class Answer { Save, Discard, Cancel };

  // Asks before `action` (for Open, of `path`); prints the question once while it is up.
  void ask(Action action, const std::string& path);
  bool active() const { return asked_.has_value(); }
  // While the question is up, the first key that answers it; the caller then drops the frame's input.
  std::optional<Answer> keyAnswer(const std::vector<InputEvent>& input) const;
  // Draws the modal; returns the answer (from `keyAnswer` or a button) once, and closes the question.
  std::optional<Answer> draw(std::optional<Answer> keyAnswer);
  // What was asked about, once answered.
  Action action() const { return action_; }
  const std::string& openPath() const { return path_; }

 private:
  std::optional<Action> asked_;
  Action action_ = Action::Quit;
  std::string path_;
};

}  // namespace rayview
