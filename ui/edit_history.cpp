#include "edit_history.h"

#include <utility>

namespace rayview {

EditHistory::EditHistory(EditState initial, std::size_t limit) : limit_(limit > 0 ? limit : 1), current_(std::move(initial)) {}

void EditHistory::record(const EditState& committed, bool inGesture) {
  if (committed == current_) {
    if (!inGesture) gestureOpen_ = false;
    return;
  }
  if (!(inGesture && gestureOpen_)) {
    undo_.push_back(std::move(current_));
    if (undo_.size() > limit_) undo_.pop_front();
    redo_.clear();
  }
  current_ = committed;
  gestureOpen_ = inGesture;
}

std::optional<EditState> EditHistory::undo() {
  if (undo_.empty()) return std::nullopt;
  redo_.push_back(std::move(current_));
  current_ = std::move(undo_.back());
  undo_.pop_back();
  gestureOpen_ = false;
  return current_;
}

std::optional<EditState> EditHistory::redo() {
  if (redo_.empty()) return std::nullopt;
  undo_.push_back(std::move(current_));
  current_ = std::move(redo_.back());
  redo_.pop_back();
  gestureOpen_ = false;
  return current_;
}

}  // namespace rayview
