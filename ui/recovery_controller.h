#pragma once
// The recovery file as the window shows it: kept in step with the unsaved edits (recovery_file.h), and, when a
// scene is opened whose file holds edits a viewer that stopped left there, the offer to restore them (a panel over
// the image, or the script's `recovery restore|discard`).

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>

#include "recovery_file.h"

namespace rayview {

class SceneSession;

class RecoveryController {
 public:
  using Clock = std::chrono::steady_clock;

  // Another scene is on screen (not a reload): its recovery file, if another viewer left one, is offered.
  void sceneOpened(const std::string& scenePath);
  // Once per loop: keeps the file in step with the edits (not while an offer is up). Prints a problem once.
  void keep(const SceneSession* session, const std::string& scenePath, Clock::time_point now);
  std::optional<double> secondsUntilDue(Clock::time_point now) const { return keeper_.secondsUntilDue(now); }
  // The process is being ended: the edits written at once. Returns what to tell the user about them.
  std::string keepNow(const SceneSession* session, const std::string& scenePath);
  // What to tell the user about the unsaved edits if the process ended now, without writing anything.
  std::string note(const SceneSession* session, const std::string& scenePath) const;
  // Unsaved edits discarded as asked: their file goes.
  void discard(const std::string& scenePath) { keeper_.discard(scenePath); }

  bool offered() const { return offer_.has_value(); }
  // Restores the offered edits into `session` (one undo step, unsaved) or discards them (the file goes). Returns
  // why not ("" when done): nothing offered, or edits that no longer fit the scene (the offer stays to discard).
  std::string answer(bool restore, SceneSession* session);
  // The offer's panel at the top of the image area (x, y, width); returns the button pressed: true restore, false
  // discard.
  std::optional<bool> draw(float x, float y, float width);
  // Where the panel's buttons were drawn last ("restore=X,Y,W,H discard=X,Y,W,H"; "" when no offer is up), for tools
  // that drive the window (RAYVIEW_PRINT_OVERLAYS).
  const std::string& buttons() const { return buttons_; }

 private:
  struct Offer {
    std::filesystem::path file;
    RecoveredEdits edits;
    std::string when;  // the file's time, as the panel says it
    std::string problem;  // why a restore failed, shown in the panel
  };
  RecoveryKeeper keeper_;
  std::optional<Offer> offer_;
  std::string buttons_;
};

}  // namespace rayview
