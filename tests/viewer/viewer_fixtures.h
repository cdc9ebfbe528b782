#pragma once
// What the viewer's logic tests share: the test scene, a loaded session's parts, scratch directories, a fake
// viewer for scripts.

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>

#include "rayview/scene_loader.h"
#include "scene_session.h"
#include "script_runner.h"
#include "support/image_compare.h"

namespace rayview::viewer_testing {

namespace fs = std::filesystem;

inline fs::path freshDirectory(const std::string& name) {
  const fs::path directory = testing::testOutputDirectory() / "viewer_logic" / name;
  fs::remove_all(directory);
  fs::create_directories(directory);
  return directory;
}

inline void writeText(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

inline const fs::path kViewerScene = testing::sourceDirectory() / "tests/viewer/viewer_scene.xml";

inline LoadedSceneParts loadParts() {
  LoadedScene loaded = loadSceneFile(kViewerScene);
  LoadedSceneParts parts;
  parts.scene = std::make_shared<const Scene>(std::move(loaded.scene));
  parts.geometry = prepareGeometry(parts.scene, AccelKind::Reference, BvhBuild::Interactive);
  parts.bounds = sceneBounds(*parts.scene);
  parts.accel = AccelKind::Reference;
  return parts;
}

// A host that records what the runner asks of the viewer.
class FakeHost : public ScriptHost {
 public:
  explicit FakeHost(SceneSession* session) : session_(session) {}
  bool imageView = false;
  SceneSession* session() override { return session_; }
  void open(const std::string& path) override {
    opened = path;
    loadingFrames = 2;
  }
  void reload() override { loadingFrames = 1; }
  void setModelUp(ModelUpAxis up) override {
    modelUp = up;
    loadingFrames = 1;
  }
  std::optional<ModelUpAxis> modelUp;
  bool loading() const override { return loadingFrames > 0; }
  std::string loadError() const override { return loadingFrames > 0 ? "" : error; }
  std::string scenePath() const override { return "scene.xml"; }
  std::uint64_t sceneSerial() const override { return serial; }
  bool finalFrameShown() const override { return final; }
  std::string editProblem() const override { return {}; }
  bool fileImageReady() override { return final; }
  void setImageView(bool on) override { imageView = on; }
  std::filesystem::path saveFrame(const std::string& path, FrameSave what) override {
    savedKind = what;
    return savedFrame = path;
  }
  std::filesystem::path saveScene(const std::string& path) override { return path; }
  void screenshot(const std::string&) override {}
  void saveView(const std::string&) override {}
  std::string stateLine() const override { return "state"; }
  void resizeWindow(int, int) override {}
  DisplayMapping displayMapping() const override { return mapping; }
  void setDisplayMapping(const DisplayMapping& m) override { mapping = m; }
  void quit(int code) override { exitCode = code; }
  void measureTradeoff(double scale) override {
    measuredScale = scale;
    tradeoff.running = true;
  }
  void cancelTradeoff() override {
    tradeoff.running = false;
    tradeoff.error = "cancelled";
  }
  TradeoffState tradeoffState() const override { return tradeoff; }
  std::string applyTradeoff(const Knob* knob, int value) override {
    applied = knob ? std::string(knob->name) + " " + std::to_string(value) : "advice";
    return applyError;
  }
  std::string loadReference(const std::string& path) override {
    referencePath = path;
    return referenceError;
  }
  std::optional<ImageError> finalComparison() const override { return final ? comparison : std::nullopt; }
  std::string comparisonProblem() const override { return sizeProblem; }

  void frame(ScriptRunner& runner) {
    runner.step(*this);
    if (loadingFrames > 0) --loadingFrames;
  }

  SceneSession* session_;
  std::string opened, error, savedFrame = "-";
  FrameSave savedKind = FrameSave::Raw;
  DisplayMapping mapping;
  int loadingFrames = 0;
  std::uint64_t serial = 1;
  bool final = false;
  int exitCode = -1;
  double measuredScale = 0.0;
  TradeoffState tradeoff;
  std::string applied, applyError;
  std::string referencePath, referenceError, sizeProblem;
  std::optional<ImageError> comparison;  // of the final pass, once final
};

}  // namespace rayview::viewer_testing
