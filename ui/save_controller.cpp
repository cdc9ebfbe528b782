// The viewer's saves: the file's image, the edited scene, the view as seen, screenshots.
#include "save_controller.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include <GLFW/glfw3.h>

#include "load_controller.h"
#include "numbered_file.h"
#include "rayview/scene_writer.h"
#include "scene_session.h"
#include "window_capture.h"

namespace rayview {

std::string suggestedSaveAsPath(const std::string& scenePath) {
  const std::filesystem::path scene = std::filesystem::path(scenePath.empty() ? "default.xml" : scenePath);
  return (scene.parent_path() / (scene.stem().string() + "_edited.xml")).string();
}

SaveController::SaveController(int threads, FilePanelState& panel) : panel_(panel), fileImageTask_(threads) {
  fileImageTask_.setFinishedListener([] { glfwPostEmptyEvent(); });
}

SaveController::FileImageKey SaveController::keyOf(const FrameSaveContext& c) {
  return {c.sceneSerial, c.session ? c.session->commitCount() : 0, c.session ? &c.session->geometry() : nullptr};
}

bool SaveController::fileImageReady(const FrameSaveContext& c) {
  if (!c.finalShown || !c.session) return false;
  if (c.imageView) return true;  // the final pass on screen is the file's image
  const FileImageKey key = keyOf(c);
  if (fileImage_ && fileImageOf_ == key) return true;
  if (awaitedFileImage_ == 0 || awaitedFileImageKey_ != key) {
    awaitedFileImage_ = fileImageTask_.start(c.session->fileSource());
    awaitedFileImageKey_ = key;
  }
  return false;
}

bool SaveController::pollFileImage() {
  std::optional<FileImageResult> result = fileImageTask_.takeResult();
  if (!result || result->id != awaitedFileImage_) return false;
  awaitedFileImage_ = 0;
  if (!result->error.empty()) {
    reportFailure(ImageIoError(result->error));
    return true;
  }
  if (result->cancelled) return true;
  fileImage_ = std::move(result->image);
  fileImageOf_ = awaitedFileImageKey_;
  std::printf("rendered the file's image %dx%d for saving in %.0f ms\n", fileImage_->width, fileImage_->height,
              result->renderMs);
  std::fflush(stdout);
  return true;
}

const Image& SaveController::fileImage(const FrameSaveContext& c) const { return c.imageView ? *c.shown : *fileImage_; }

std::filesystem::path SaveController::saveFrame(const FrameSaveContext& c, const std::string& path, FrameSave what) {
  if (!c.shown) throw ImageIoError("no frame to save yet");
  // Callers wait for it: the final pass (image view) or the file's image rendered after it (window view); never a
  // coarse pass, which holds one sample per block, nor the window's other resolution.
  if (!fileImageReady(c)) throw ImageIoError("the file's image is not rendered yet");
  return writeFrame(fileImage(c), c.scenePath, c.mapping, path, what);
}

std::filesystem::path SaveController::writeFrame(const Image& raw, const std::string& scenePath,
                                                 const DisplayMapping& mapping, const std::string& path, FrameSave what) {
  // Raw: as `rayview render` writes it. Displayed: with the exposure and gamma on screen, which at their defaults
  // is the same image.
  Image mapped;
  if (what == FrameSave::Displayed) mapped = mapForDisplay(raw, mapping);
  const Image& image = what == FrameSave::Displayed ? mapped : raw;
  std::filesystem::path saved = path;
  if (path.empty()) saved = saveFrameNumbered(image, scenePath, what);
  else writeImageFile(refusingInputs(path, scenePath, nullptr), image);
  pending_.reset();
  panel_.frameSavePending = false;
  panel_.lastSaveFailed = false;
  panel_.lastSaved = "saved " + saved.string();
  if (what == FrameSave::Displayed) panel_.lastSaved += " (as displayed: " + describe(mapping) + ")";
  std::printf("saved %s\n", saved.string().c_str());
  std::fflush(stdout);
  return saved;
}

std::filesystem::path SaveController::saveScene(SceneSession* session, const std::string& scenePath,
                                                const std::string& path) {
  if (!session) throw ImageIoError("no scene to save yet");
  // What is on screen: the committed edits (identical to the fields unless a field holds an invalid value).
  const SceneParameters& parameters = session->committedEdits();
  std::filesystem::path saved = path;
  if (path.empty()) saved = saveSceneNumbered(parameters, session->loaded(), scenePath);
  else writeSceneFile(path, parameters, session->loaded());
  session->markSaved(parameters);
  // Written over the open file itself: the title loses its `*`; saved elsewhere, the open file still differs.
  std::error_code error;
  if (!scenePath.empty() && std::filesystem::equivalent(saved, scenePath, error)) session->markWrittenToFile(parameters);
  panel_.lastSaveFailed = false;
  panel_.lastSaved = "saved scene " + saved.string();
  std::printf("saved scene %s\n", saved.string().c_str());
  std::fflush(stdout);
  return saved;
}

void SaveController::reportFailure(const std::exception& error) {
  pending_.reset();
  panel_.frameSavePending = false;
  panel_.lastSaveFailed = true;
  panel_.lastSaved = std::string("not saved: ") + error.what();
  std::fprintf(stderr, "rayview: %s\n", panel_.lastSaved.c_str());
}

void SaveController::toastPanelLine() {
  const double seconds = panel_.lastSaveFailed ? kFailedToastSeconds : kToastSeconds;
  toast_ = SaveToast{panel_.lastSaved, panel_.lastSaveFailed,
                     std::chrono::steady_clock::now() +
                         std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(seconds))};
}

const SaveToast* SaveController::toast(std::chrono::steady_clock::time_point now) const {
  return toast_ && now < toast_->until ? &*toast_ : nullptr;
}

std::optional<double> SaveController::secondsUntilToastEnds(std::chrono::steady_clock::time_point now) const {
  if (!toast(now)) return std::nullopt;
  return std::chrono::duration<double>(toast_->until - now).count();
}

void SaveController::saveFrameReporting(const FrameSaveContext& c) {
  // Ctrl+S saves the file's image, identical to `rayview render`, never a coarse pass, and of the state it was
  // pressed in. While refining, the render goes on and the save happens when that state's image is ready
  // (pollPending); in the window view the file's image is rendered in the background, its progress in the Save panel.
  const FrameSave what = panel_.saveFrameDisplayed ? FrameSave::Displayed : FrameSave::Raw;
  if (!fileImageReady(c)) {
    if (!pending_ && c.session) {
      pending_ = PendingFrameSave{keyOf(c), c.session->fileSource(), what, c.mapping};
      panel_.frameSavePending = true;
      panel_.lastSaveFailed = false;
      panel_.lastSaved = "saving when the final pass is ready...";
      std::printf("saving when the final pass is ready\n");
      std::fflush(stdout);
      toastPanelLine();
    }
    return;
  }
  try {
    saveFrame(c, {}, what);
  } catch (const std::exception& error) {
    reportFailure(error);
  }
  toastPanelLine();
}

void SaveController::saveSceneReporting(SceneSession* session, const std::string& scenePath, const std::string& path) {
  try {
    saveScene(session, scenePath, path);
  } catch (const std::exception& error) {
    reportFailure(error);
  }
  toastPanelLine();
}

void SaveController::pollPending(const FrameSaveContext& c) {
  if (!pending_) return;
  if (keyOf(c) != pending_->key) {
    savePressedState(c);
    return;
  }
  if (!fileImageReady(c)) return;
  try {
    saveFrame(c, {}, pending_->what);
  } catch (const std::exception& error) {
    reportFailure(error);
  }
  toastPanelLine();
}

bool SaveController::savePressedState(const FrameSaveContext& c) {
  if (!fileImage_ || fileImageOf_ != pending_->key) {
    if (awaitedFileImage_ == 0 || awaitedFileImageKey_ != pending_->key) {
      awaitedFileImage_ = fileImageTask_.start(pending_->source);
      awaitedFileImageKey_ = pending_->key;
    }
    return false;
  }
  try {
    writeFrame(*fileImage_, c.scenePath, pending_->mapping, {}, pending_->what);
  } catch (const std::exception& error) {
    reportFailure(error);
  }
  toastPanelLine();
  return true;
}

void SaveController::showProgress(const SceneSession* session) {
  if (!panel_.frameSavePending || awaitedFileImage_ == 0 || !session) return;
  const Camera& file = session->committedEdits().camera;
  panel_.lastSaved = "rendering the file's " + std::to_string(file.width) + "x" + std::to_string(file.height) +
                     " image to save: " + std::to_string(static_cast<int>(100.0 * fileImageTask_.progress())) + "%";
}

void SaveController::sceneReplaced(bool anotherScene) {
  fileImageTask_.cancel();
  awaitedFileImage_ = 0;
  fileImage_.reset();
  if (!anotherScene) return;
  // The save messages were about the previous scene, and a frame save still waiting for its final pass would save
  // this scene's image under the old name.
  if (panel_.frameSavePending) std::fprintf(stderr, "rayview: frame not saved: another scene was opened\n");
  pending_.reset();
  panel_.frameSavePending = false;
  panel_.lastSaved.clear();
  panel_.lastSaveFailed = false;
}

void SaveController::writeCaptures(int framebufferWidth, int framebufferHeight, const ViewerLayout& l, bool haveFrame,
                                   const std::string& scenePath) {
  if (pendingViewSave_) {
    writeViewSave(framebufferWidth, framebufferHeight, l, haveFrame, scenePath);
    if (std::exchange(viewSaveFromUser_, false)) toastPanelLine();
  }
  if (!pendingScreenshot_.empty()) writeScreenshot(framebufferWidth, framebufferHeight);
}

void SaveController::writeScreenshot(int framebufferWidth, int framebufferHeight) {
  const std::string path = std::exchange(pendingScreenshot_, {});
  try {
    writeImageFile(path, readWindowPixels(framebufferWidth, framebufferHeight));
    captureOutcome_ = std::string();
    std::printf("screenshot %s\n", path.c_str());
    std::fflush(stdout);
  } catch (const ImageIoError& error) {
    captureOutcome_ = error.what();
    panel_.lastSaved = std::string("screenshot failed: ") + error.what();
    panel_.lastSaveFailed = true;
    std::fprintf(stderr, "rayview: %s\n", error.what());
  }
}

void SaveController::writeViewSave(int framebufferWidth, int framebufferHeight, const ViewerLayout& l, bool haveFrame,
                                   const std::string& scenePath) {
  const std::string path = std::exchange(*pendingViewSave_, {});
  pendingViewSave_.reset();
  try {
    if (!haveFrame) throw ImageIoError("no frame to save yet");
    // The image area in framebuffer pixels, rows from the top.
    const Image window = readWindowPixels(framebufferWidth, framebufferHeight);
    const int x0 = std::clamp(static_cast<int>(std::lround(l.viewX * l.framebufferScale)), 0, window.width);
    const int y0 = std::clamp(static_cast<int>(std::lround(l.viewY * l.framebufferScale)), 0, window.height);
    const int x1 = std::clamp(static_cast<int>(std::lround((l.viewX + l.viewWidth) * l.framebufferScale)), x0, window.width);
    const int y1 = std::clamp(static_cast<int>(std::lround((l.viewY + l.viewHeight) * l.framebufferScale)), y0, window.height);
    if (x1 <= x0 || y1 <= y0) throw ImageIoError("the image area is empty");
    Image view(x1 - x0, y1 - y0);
    for (int y = y0; y < y1; ++y)
      std::copy_n(window.pixel(x0, y), static_cast<std::size_t>(x1 - x0) * 3, view.pixel(0, y - y0));
    std::filesystem::path saved = path;
    if (path.empty()) saved = saveFrameNumbered(view, scenePath, FrameSave::View);
    else writeImageFile(refusingInputs(path, scenePath, nullptr), view);
    captureOutcome_ = std::string();
    panel_.lastSaveFailed = false;
    panel_.lastSaved = "saved the view as seen: " + saved.string();
    std::printf("saved view %s\n", saved.string().c_str());
    std::fflush(stdout);
  } catch (const ImageIoError& error) {
    panel_.lastSaved = std::string("view not saved: ") + error.what();
    panel_.lastSaveFailed = true;
    captureOutcome_ = error.what();
    std::fprintf(stderr, "rayview: view not saved: %s\n", error.what());
  }
}

}  // namespace rayview
