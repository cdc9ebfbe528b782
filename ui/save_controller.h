#pragma once
// Saving from the viewer: the file's image (Ctrl+S, Save frame, save-frame; in the window view rendered in the
// background at the file's resolution), the edited scene, the view as seen and screenshots read back from the
// window. Each save is reported in the Save panel and on stdout or stderr, never as an exception to the user.

#include <chrono>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "display_mapping.h"
#include "file_image_task.h"
#include "panels.h"
#include "viewer_layout.h"

namespace rayview {

// What saving the file's image needs of the rest of the viewer, as it is now.
struct FrameSaveContext {
  const SceneSession* session = nullptr;  // null before a scene has loaded
  std::uint64_t sceneSerial = 0;
  bool finalShown = false;            // the final pass of the current edits is on screen
  bool imageView = false;             // the pass on screen is the file's image (the image view)
  const Image* shown = nullptr;       // the pass on screen; null before the first
  std::string scenePath;              // "" for the embedded default scene
  DisplayMapping mapping;             // exposure and gamma on screen
};

// The outcome of the last save the user asked for (keys, buttons), shown over the image for a while, so that it is
// seen with the panels hidden or scrolled away. Scripts' saves print their lines instead.
struct SaveToast {
  std::string text;
  bool failed = false;
  std::chrono::steady_clock::time_point until{};
};
inline constexpr double kToastSeconds = 5.0;
inline constexpr double kFailedToastSeconds = 12.0;  // long enough to read a path and a reason

// "Save scene as" starts with scene_edited.xml beside the scene, written the way the user named the scene.
std::string suggestedSaveAsPath(const std::string& scenePath);

class SaveController {
 public:
  // `panel`: the Save panel's state, where every save's outcome is shown.
  SaveController(int threads, FilePanelState& panel);

  // The image a frame save writes is ready: in the image view the final pass on screen; in the window view the
  // file's image rendered in the background, which this starts once the final pass is on screen.
  bool fileImageReady(const FrameSaveContext& context);
  // Writes it ("" = numbered beside the scene), raw or as displayed; throws on failure (also when not ready).
  std::filesystem::path saveFrame(const FrameSaveContext& context, const std::string& path, FrameSave what);
  // Writes the committed edits ("" = numbered); throws on failure.
  std::filesystem::path saveScene(SceneSession* session, const std::string& scenePath, const std::string& path);
  // Ctrl+S: saves now, or the image of the state it was pressed in once that is rendered (pollPending): later
  // edits (an orbit after the press) never go into it.
  void saveFrameReporting(const FrameSaveContext& context);
  void saveSceneReporting(SceneSession* session, const std::string& scenePath, const std::string& path);
  // A frame save waiting for its image: saves it when it is ready. While the state is still the one it was
  // pressed in, that is the final pass (or the file's image rendered after it); after an edit, the pressed
  // state's file image rendered in the background.
  void pollPending(const FrameSaveContext& context);
  // Takes the background render of the file's image; true when one arrived (or was cancelled).
  bool pollFileImage();
  // The background render for saving is running (its progress is drawn).
  bool renderingFileImage() const { return awaitedFileImage_ != 0; }
  // The Save panel's line while a save waits for the background render.
  void showProgress(const SceneSession* session);
  // Another scene (or a reload) is on screen: the file's image is of the old one; with `anotherScene`, the
  // messages and a waiting save are too.
  void sceneReplaced(bool anotherScene);

  // The whole window as PNG, and the image area as seen: taken when this frame has been drawn.
  void requestScreenshot(const std::string& path) {
    pendingScreenshot_ = path;
    captureOutcome_.reset();
  }
  // `fromUser`: the button, whose outcome is also shown as a toast.
  void requestViewSave(const std::string& path, bool fromUser = false) {
    pendingViewSave_ = path;
    viewSaveFromUser_ = fromUser;
    captureOutcome_.reset();
  }
  // The newest screenshot's or view save's outcome once written: "" saved, else why not (a script fails on it).
  const std::optional<std::string>& captureOutcome() const { return captureOutcome_; }
  bool captureRequested() const { return !pendingScreenshot_.empty() || pendingViewSave_.has_value(); }
  bool viewSaveRequested() const { return pendingViewSave_.has_value(); }
  // Reads the frame just drawn (before the swap) for the captures asked for.
  void writeCaptures(int framebufferWidth, int framebufferHeight, const ViewerLayout& layout, bool haveFrame,
                     const std::string& scenePath);

  // The toast on screen now, if any; seconds until it goes (the UI wakes then to take it away).
  const SaveToast* toast(std::chrono::steady_clock::time_point now) const;
  std::optional<double> secondsUntilToastEnds(std::chrono::steady_clock::time_point now) const;

 private:
  // The state the file's image (or the running request) is of: made once per state, never saved for other edits.
  struct FileImageKey {
    std::uint64_t scene = 0, commit = 0;
    const void* geometry = nullptr;
    bool operator==(const FileImageKey&) const = default;
  };
  // Ctrl+S pressed before its image was ready: the state it was pressed in, and how to save it.
  struct PendingFrameSave {
    FileImageKey key;
    std::shared_ptr<const PixelSource> source;  // the file's image of that state
    FrameSave what = FrameSave::Raw;
    DisplayMapping mapping;
  };
  static FileImageKey keyOf(const FrameSaveContext& context);
  const Image& fileImage(const FrameSaveContext& context) const;
  // Writes `raw` (or it mapped for display) and reports it; throws on failure.
  std::filesystem::path writeFrame(const Image& raw, const std::string& scenePath, const DisplayMapping& mapping,
                                   const std::string& path, FrameSave what);
  // The pressed state's image, rendered in the background: true once saved (or failed).
  bool savePressedState(const FrameSaveContext& context);
  void reportFailure(const std::exception& error);
  // Shows what the Save panel says now as the toast.
  void toastPanelLine();
  void writeViewSave(int framebufferWidth, int framebufferHeight, const ViewerLayout& layout, bool haveFrame,
                     const std::string& scenePath);
  void writeScreenshot(int framebufferWidth, int framebufferHeight);

  FilePanelState& panel_;
  FileImageTask fileImageTask_;
  std::uint64_t awaitedFileImage_ = 0;
  FileImageKey awaitedFileImageKey_, fileImageOf_;
  std::optional<Image> fileImage_;
  std::optional<PendingFrameSave> pending_;
  std::string pendingScreenshot_;
  std::optional<std::string> pendingViewSave_;  // "Save view as seen" ("": a numbered file), after this frame
  bool viewSaveFromUser_ = false;
  std::optional<std::string> captureOutcome_;
  std::optional<SaveToast> toast_;
};

}  // namespace rayview
