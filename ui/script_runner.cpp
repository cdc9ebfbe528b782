#include "script_runner.h"

#include <algorithm>
#include <cstdio>
#include <utility>

#include "rayview/knobs.h"
#include "reference_compare.h"
#include "scene_session.h"

namespace rayview {
namespace {

constexpr double kRadiansPerDegree = 3.14159265358979323846 / 180.0;

glm::dvec3 vec3(const std::vector<double>& n) { return {n[0], n[1], n[2]}; }
Color color(const std::vector<double>& n) {
  return {static_cast<float>(n[0]), static_cast<float>(n[1]), static_cast<float>(n[2])};
}

template <typename T>
std::string idList(const std::vector<T>& items) {
  std::string list;
  for (const T& item : items) list += (list.empty() ? "" : ", ") + item.id;
  return list.empty() ? "none" : list;
}

std::chrono::steady_clock::duration seconds(double s) {
  // Saturated as well as refused when parsed (kMaxScriptSeconds): a cast past the clock's range is undefined.
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(std::clamp(s, 0.0, kMaxScriptSeconds)));
}

}  // namespace

void ScriptRunner::fail(const std::string& message) {
  failure_ = (current_ ? current_->where(script_.file) : script_.file) + ": " + message;
}

void ScriptRunner::step(ScriptHost& host) {
  if (!running()) return;
  // The script starts once the scene named on the command line is on screen (or has failed to load).
  if (!initialLoadSeen_) {
    if (host.loading()) return;
    initialLoadSeen_ = true;
  }
  if (wait_ != Wait::None) {
    try {
      if (!waitIsOver(host)) return;
    } catch (const std::exception& error) {
      wait_ = Wait::None;
      return fail(error.what());
    }
    const Wait finished = std::exchange(wait_, Wait::None);
    // A failed open fails the script, unless the very next command is the expect-error that checks it.
    if (finished == Wait::Load && !host.loadError().empty() &&
        (next_ >= script_.commands.size() || script_.commands[next_].name != "expect-error"))
      return fail("open failed: " + host.loadError());
  }
  if (next_ >= script_.commands.size()) return;
  current_ = &script_.commands[next_++];
  try {
    start(*current_, host);
  } catch (const std::exception& error) {
    fail(error.what());
  }
}

bool ScriptRunner::waitIsOver(ScriptHost& host) {
  const bool late = Clock::now() >= deadline_;
  switch (wait_) {
    case Wait::None:
      return true;
    case Wait::SaveFrame:
    case Wait::Final:
      if (const std::string problem = host.editProblem(); !problem.empty()) {
        fail("the edits cannot be rendered: " + problem);
        return false;
      }
      if (wait_ == Wait::Final && host.finalFrameShown() && !host.loading()) return true;
      // save-frame saves what Ctrl+S saves: the file's image as `rayview render` writes it (the final pass in the
      // image view, rendered in the background in the window view); save-frame-displayed the same with the
      // exposure and gamma on screen applied.
      if (wait_ == Wait::SaveFrame && !host.loading() && host.fileImageReady()) {
        host.saveFrame(current_->args.empty() ? std::string() : current_->args[0],
                       current_->name == "save-frame-displayed" ? FrameSave::Displayed : FrameSave::Raw);
        return true;
      }
      if (late) fail("no final pass within " + std::to_string(current_->numbers.empty() ? kDefaultWaitFinalSeconds
                                                                                          : current_->numbers[0]) +
                     " s");
      return false;
    case Wait::Compare: {
      if (const std::string problem = host.editProblem(); !problem.empty()) {
        fail("the edits cannot be rendered: " + problem);
        return false;
      }
      if (const std::string problem = host.comparisonProblem(); !problem.empty()) {
        fail("compare: " + problem);
        return false;
      }
      const std::optional<ImageError> figures = host.finalFrameShown() && !host.loading() ? host.finalComparison()
                                                                                          : std::nullopt;
      if (figures) {
        std::printf("%s\n", comparisonLine(current_->args[0], *figures).c_str());
        std::fflush(stdout);
        return true;
      }
      if (late) fail("compare: no final pass within " + std::to_string(kDefaultWaitFinalSeconds) + " s");
      return false;
    }
    case Wait::Load:
      if (!host.loading()) return true;
      if (late) fail("the scene did not load within " + std::to_string(kDefaultLoadSeconds) + " s");
      return false;
    case Wait::Frames:
      return framesLeft_ == 0 || --framesLeft_ == 0;
    case Wait::Capture:
      // Taken after the next frame is drawn: the script goes on once it is written, and fails when it was not.
      if (const std::optional<std::string> outcome = host.captureOutcome()) {
        if (!outcome->empty()) fail(current_->name + ": " + *outcome);
        return outcome->empty();
      }
      if (late) fail(current_->name + ": not taken within " + std::to_string(kDefaultWaitFinalSeconds) + " s");
      return false;
    case Wait::Until:
      return late;
    case Wait::Tradeoff: {
      const TradeoffState state = host.tradeoffState();
      if (state.running) {
        if (late) {
          host.cancelTradeoff();
          fail("the measurement did not finish within " + std::to_string(current_->numbers[1]) + " s");
        }
        return false;
      }
      if (!state.error.empty()) {
        fail("measure-tradeoff: " + state.error);
        return false;
      }
      std::printf("tradeoff %d points\n", state.points);
      std::fflush(stdout);
      return true;
    }
  }
  return true;
}

void ScriptRunner::start(const ScriptCommand& c, ScriptHost& host) {
  const std::string& name = c.name;
  if (name == "wait-final") {
    wait_ = Wait::Final;
    deadline_ = Clock::now() + seconds(c.numbers.empty() ? kDefaultWaitFinalSeconds : c.numbers[0]);
  } else if (name == "wait-frames") {
    wait_ = Wait::Frames;
    framesLeft_ = static_cast<std::uint64_t>(c.numbers[0]);
  } else if (name == "sleep") {
    wait_ = Wait::Until;
    deadline_ = Clock::now() + seconds(c.numbers[0]);
  } else if (name == "model-up" || name == "open" || name == "reload") {
    pathBeforeOpen_ = host.scenePath();
    serialBeforeOpen_ = host.sceneSerial();
    if (name == "open") host.open(c.args[0]);
    else if (name == "reload") host.reload();
    else host.setModelUp(c.args[0] == "z" ? ModelUpAxis::Z : ModelUpAxis::Y);
    wait_ = Wait::Load;
    deadline_ = Clock::now() + seconds(kDefaultLoadSeconds);
  } else if (name == "expect-error") {
    checkExpectedError(c, host);
  } else if (name == "expect-no-error") {
    if (!host.loadError().empty()) fail("expected no error, the error panel shows: " + host.loadError());
  } else if (name == "set") {
    applySet(c, host);
  } else if (name == "camera") {
    applyCamera(c, host);
  } else if (name == "save-frame" || name == "save-frame-displayed") {
    wait_ = Wait::SaveFrame;
    deadline_ = Clock::now() + seconds(kDefaultWaitFinalSeconds);
  } else if (name == "save-scene") {
    host.saveScene(c.args.empty() ? std::string() : c.args[0]);
  } else if (name == "screenshot") {
    host.screenshot(c.args[0]);
    wait_ = Wait::Capture;
    deadline_ = Clock::now() + seconds(kDefaultWaitFinalSeconds);
  } else if (name == "save-view") {
    host.saveView(c.args.empty() ? std::string() : c.args[0]);
    wait_ = Wait::Capture;
    deadline_ = Clock::now() + seconds(kDefaultWaitFinalSeconds);
  } else if (name == "measure-tradeoff") {
    host.measureTradeoff(c.numbers[0]);
    wait_ = Wait::Tradeoff;
    deadline_ = Clock::now() + seconds(c.numbers[1]);
  } else if (name == "compare") {
    if (const std::string error = host.loadReference(c.args[0]); !error.empty()) return fail("compare: " + error);
    wait_ = Wait::Compare;
    deadline_ = Clock::now() + seconds(kDefaultWaitFinalSeconds);
  } else if (name == "tradeoff-apply") {
    const Knob* knob = c.args[0] == "advice" ? nullptr : findKnob(c.args[0]);
    if (const std::string why = host.applyTradeoff(knob, knob ? static_cast<int>(c.numbers[0]) : 0); !why.empty())
      fail("tradeoff-apply: " + why);
  } else if (name == "recovery") {
    if (const std::string why = host.answerRecovery(c.args[0] == "restore"); !why.empty()) fail("recovery: " + why);
  } else if (name == "undo" || name == "redo") {
    SceneSession* session = host.session();
    if (!session) return fail("no scene is loaded");
    // Nothing to undo (or redo) is not an error: print-state shows how many steps there are.
    if (name == "undo") session->undo();
    else session->redo();
  } else if (name == "pick") {
    SceneSession* session = host.session();
    if (!session) return fail("no scene is loaded");
    const std::optional<PickResult> pick = session->pick(static_cast<int>(c.numbers[0]), static_cast<int>(c.numbers[1]));
    std::printf("%s\n", pick ? describePick(*pick, session->loaded(), session->edits()).c_str() : "picked nothing");
    std::fflush(stdout);
  } else if (name == "view") {
    host.setImageView(c.args[0] == "image");
  } else if (name == "print-state") {
    std::printf("%s\n", host.stateLine().c_str());
    std::fflush(stdout);
  } else if (name == "resize") {
    host.resizeWindow(static_cast<int>(c.numbers[0]), static_cast<int>(c.numbers[1]));
  } else if (name == "quit") {
    host.quit(c.numbers.empty() ? 0 : static_cast<int>(c.numbers[0]));
  } else {
    fail("unknown command '" + name + "'");  // parseScript lets none through
  }
}

void ScriptRunner::checkExpectedError(const ScriptCommand& c, ScriptHost& host) {
  const std::string error = host.loadError();
  if (error.empty()) return fail("expected an error containing '" + c.args[0] + "', but no error is shown");
  if (error.find(c.args[0]) == std::string::npos)
    return fail("expected an error containing '" + c.args[0] + "', the error panel shows: " + error);
  // The failed load must have left the previous scene on screen.
  if (host.scenePath() != pathBeforeOpen_ || host.sceneSerial() != serialBeforeOpen_)
    return fail("the failed load replaced the scene on screen");
}

void ScriptRunner::applySet(const ScriptCommand& c, ScriptHost& host) {
  // Display settings need no scene: they apply to whatever the image area shows.
  if (c.args[0] == "exposure" || c.args[0] == "gamma") {
    DisplayMapping mapping = host.displayMapping();
    (c.args[0] == "exposure" ? mapping.exposureStops : mapping.gamma) = static_cast<float>(c.numbers[0]);
    return host.setDisplayMapping(mapping);
  }
  SceneSession* session = host.session();
  if (!session) return fail("no scene is loaded");
  SceneParameters& edits = session->edits();
  RenderSettings& settings = session->settings();
  const std::string& what = c.args[0];
  const std::vector<double>& n = c.numbers;
  if (const Knob* knob = findKnob(what)) {
    knob->set(edits, settings, static_cast<int>(n[0]));
  } else if (what == "background") {
    edits.background = color(n);
  } else if (what == "ambient") {
    edits.ambientLight = color(n);
  } else if (what == "material") {
    const int index = findMaterial(edits, c.args[1]);
    if (index < 0) return fail("no material '" + c.args[1] + "' (materials: " + idList(edits.materials) + ")");
    Material& m = edits.materials[static_cast<std::size_t>(index)];
    const std::string& property = c.args[2];
    if (property == "ambient") m.ambient = color(n);
    else if (property == "diffuse") m.diffuse = color(n);
    else if (property == "specular") m.specular = color(n);
    else if (property == "mirror") m.mirror = color(n);
    else if (property == "phong") m.phongExponent = static_cast<float>(n[0]);
    else if (property == "texture-factor") m.textureFactor = static_cast<float>(n[0]);
  } else if (what == "light") {
    const std::string& id = c.args[1];
    const std::string& property = c.args[2];
    if (!setLightValue(edits.lights, id, property, vec3(n)))
      return fail("no light '" + id + "' with a " + property + " (" + lightIds(edits.lights) + ")");
  }
}

void ScriptRunner::applyCamera(const ScriptCommand& c, ScriptHost& host) {
  SceneSession* session = host.session();
  if (!session) return fail("no scene is loaded");
  Camera& camera = session->edits().camera;
  const std::string& what = c.args[0];
  const std::vector<double>& n = c.numbers;
  if (what == "orbit") {
    session->navigate([&](OrbitCamera& o) { o.orbit(n[0] * kRadiansPerDegree, n[1] * kRadiansPerDegree); });
  } else if (what == "pan") {
    session->navigate([&](OrbitCamera& o) { o.pan(n[0], n[1]); });
  } else if (what == "dolly") {
    session->navigate([&](OrbitCamera& o) { o.dolly(n[0]); });
  } else if (what == "frame") {
    session->navigate([&](OrbitCamera& o) { o.frame(session->framingBounds()); });
  } else if (what == "reset") {
    session->navigate([](OrbitCamera& o) { o.reset(); });
  } else if (what == "position") {
    camera.position = vec3(n);
  } else if (what == "gaze") {
    camera.gaze = vec3(n);
  } else if (what == "up") {
    camera.up = vec3(n);
  } else if (what == "near-plane") {
    camera.left = n[0];
    camera.right = n[1];
    camera.bottom = n[2];
    camera.top = n[3];
  } else if (what == "near-distance") {
    camera.nearDistance = n[0];
  } else if (what == "resolution") {
    camera.width = static_cast<int>(n[0]);
    camera.height = static_cast<int>(n[1]);
  }
}

}  // namespace rayview
