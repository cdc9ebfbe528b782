#pragma once
// Unsaved edits kept on disk while the viewer runs, so that a crash, a kill or a lost MPI rank does not take them
// along (as Blender's autosave): one file per scene, the edited parameters only (camera, lights, materials, depth,
// background; never the meshes), written whole (temporary file + rename) at most kRecoveryInterval after an edit,
// in RAYVIEW_RECOVERY_DIR, else $XDG_STATE_HOME/rayview, else ~/.local/state/rayview. The next viewer that opens the
// scene offers to restore them. No GL, no ImGui, no threads: the UI loop calls it.

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "rayview/scene.h"

namespace rayview {

class SceneSession;

inline constexpr std::chrono::milliseconds kRecoveryInterval{1000};
// What a recovery file is recorded as when read (rayview/input_files.h): the one input its keeper may replace.
inline constexpr std::string_view kRecoveryRole = "the viewer's recovery file";

// Where the recovery files go; empty when no variable names a place (no HOME).
std::filesystem::path recoveryDirectory();
// The file for the edits of `scenePath` ("" the embedded default scene): its name and a hash of its absolute path.
std::filesystem::path recoveryFileFor(const std::string& scenePath);

struct RecoveredEdits {
  std::string scenePath;  // the scene they are edits of
  SceneParameters edits;
  std::filesystem::file_time_type written;
};
// The edits as a scene file without meshes, with the scene's path in its first line. Throws ImageIoError.
void writeRecoveryFile(const std::filesystem::path& file, const std::string& scenePath, const SceneParameters& edits);
// nullopt when there is no file; throws SceneError naming the file when it cannot be read.
std::optional<RecoveredEdits> readRecoveryFile(const std::filesystem::path& file);
// Empty when `recovered` fits `loaded` (the same materials by id, the same number of each light type); else why
// not: the scene file changed since.
std::string recoveryMismatch(const SceneParameters& recovered, const SceneParameters& loaded);

// Keeps the recovery file of the scene on screen in step with its unsaved edits.
class RecoveryKeeper {
 public:
  using Clock = std::chrono::steady_clock;

  // Once per loop: writes the edits when they changed and kRecoveryInterval has passed since the last write;
  // removes the file once there is nothing unsaved (undone, saved). Does nothing while `paused` (a recovery offer
  // is up: the file holds what it offers). Returns a problem to show once ("" when none).
  std::string keep(const SceneSession* session, const std::string& scenePath, bool paused, Clock::time_point now);
  // The process is being ended: the unsaved edits written now, whatever the interval. Returns the file that holds
  // them (empty when nothing is unsaved or it could not be written, `problem` then says why).
  std::filesystem::path keepNow(const SceneSession* session, const std::string& scenePath, std::string& problem);
  // What the file of the scene on screen holds, when this process wrote it.
  const std::optional<SceneParameters>& written() const { return written_; }
  // Seconds until keep() must run again to stay within kRecoveryInterval; nullopt when nothing waits.
  std::optional<double> secondsUntilDue(Clock::time_point now) const;
  // Another scene is on screen: the previous one's file stays only if its edits were unsaved when it left.
  void sceneReplaced() { written_.reset(); }
  // The unsaved edits of `scenePath` are discarded as asked (quit, another scene opened, a script's open or quit):
  // the file this process wrote goes.
  void discard(const std::string& scenePath);

 private:
  std::optional<SceneParameters> written_;  // what the file of the scene on screen holds, when this process wrote it
  std::optional<Clock::time_point> dueAt_;  // an edit waits to be written by then
  Clock::time_point lastWrite_{};
  std::string lastProblem_;
};

}  // namespace rayview
