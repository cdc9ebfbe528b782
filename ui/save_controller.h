#pragma once
// Saving from the viewer: the file's image (Ctrl+S, Save frame, save-frame; in the window view rendered in the
// background at the file's resolution), the edited scene, the view as seen and screenshots read back from the
// window. Each save is reported in the Save panel and on stdout or stderr, never as an exception to the user.

#include <cstdint>
#include <exception>
#include <filesystem>
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
  // Ctrl+S: saves now, or once the file's image is ready (pollPending).
  void saveFrameReporting(const FrameSaveContext& context);
  void saveSceneReporting(SceneSession* session, const std::string& scenePath, const std::string& path);
  // A frame save waiting for its image: saves it when it is ready.
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
  void requestScreenshot(const std::string& path) { pendingScreenshot_ = path; }
  void requestViewSave(const std::string& path) { pendingViewSave_ = path; }
  bool captureRequested() const { return !pendingScreenshot_.empty() || pendingViewSave_.has_value(); }
  bool viewSaveRequested() const { return pendingViewSave_.has_value(); }
  // Reads the frame just drawn (before the swap) for the captures asked for.
  void writeCaptures(int framebufferWidth, int framebufferHeight, const ViewerLayout& layout, bool haveFrame,
                     const std::string& scenePath);

 private:
  // The state the file's image (or the running request) is of: made once per state, never saved for other edits.
  struct FileImageKey {
    std::uint64_t scene = 0, commit = 0;
    const void* geometry = nullptr;
    bool operator==(const FileImageKey&) const = default;
  };
  static FileImageKey keyOf(const FrameSaveContext& context);
  const Image& fileImage(const FrameSaveContext& context) const;
  void reportFailure(const std::exception& error);
  void writeViewSave(int framebufferWidth, int framebufferHeight, const ViewerLayout& layout, bool haveFrame,
                     const std::string& scenePath);
  void writeScreenshot(int framebufferWidth, int framebufferHeight);

  FilePanelState& panel_;
  FileImageTask fileImageTask_;
  std::uint64_t awaitedFileImage_ = 0;
  FileImageKey awaitedFileImageKey_, fileImageOf_;
  std::optional<Image> fileImage_;
  std::string pendingScreenshot_;
  std::optional<std::string> pendingViewSave_;  // "Save view as seen" ("": a numbered file), after this frame
};

}  // namespace rayview
