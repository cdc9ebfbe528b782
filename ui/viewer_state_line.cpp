// print-state: the viewer's state in one line, for scripts and tests.
#include <cstdio>

#include "viewer_app.h"
#include "rayview/scene_writer.h"

namespace rayview {
namespace {

std::string vectorText(const glm::dvec3& v) { return formatNumber(v.x) + "," + formatNumber(v.y) + "," + formatNumber(v.z); }

// The scene's part: camera, depth, render settings, undo and the picked mesh.
std::string sessionState(const SceneSession& s) {
  const Camera& c = s.edits().camera;
  return " position=" + vectorText(c.position) + " gaze=" + vectorText(c.gaze) + " up=" + vectorText(c.up) +
         " resolution=" + std::to_string(c.width) + "x" + std::to_string(c.height) +
         " depth=" + std::to_string(s.edits().maxRayDepth) +
         " tri_light=" + std::string(toString(s.settings().triangularLightModel)) +
         " light_samples=" + std::to_string(s.settings().lightSamples) + " unsaved=" + (s.unsaved() ? "1" : "0") +
         " undo=" + std::to_string(s.history().undoSteps()) + " redo=" + std::to_string(s.history().redoSteps()) +
         " picked=" +
         (s.selection() && s.selection()->mesh < s.loaded().meshes.size() ? s.loaded().meshes[s.selection()->mesh].id
                                                                           : std::string("none"));
}

}  // namespace

std::string ViewerApp::stateLine() const {
  const bool have = render_.haveFrame();
  const ProgressiveFrame& f = render_.frame();
  const ViewerStats& stats = render_.stats();
  std::string line = "state generation=" + std::to_string(render_.generation()) +
                     " stride=" + std::to_string(have ? f.stride : 0) +
                     " samples=" + std::to_string(have ? f.samples.done : 0) + "/" +
                     std::to_string(have ? f.samples.total : 0) + " final=" + (finalFrameShown() ? "1" : "0") +
                     " view=" + (display_.imageView ? "image" : "window") + " shown=" + std::to_string(have ? f.width : 0) +
                     "x" + std::to_string(have ? f.height : 0);
  if (const SceneSession* s = load_.session()) line += sessionState(*s);
  char figures[160];
  std::snprintf(figures, sizeof figures, " first_pass_ms=%.1f final_pass_ms=%.1f memory_mib=%.1f peak_mib=%.1f",
                stats.editToFirstPassMs, stats.editToFinalPassMs, static_cast<double>(stats.residentBytes) / (1 << 20),
                static_cast<double>(stats.peakResidentBytes) / (1 << 20));
  line += figures;
  line += " exposure=" + formatNumber(display_.mapping.exposureStops) + " gamma=" + formatNumber(display_.mapping.gamma);
  if (load_.session()) line += " traversal=" + std::string(toString(stats.accel));
  line += std::string(" recovery=") + (recovery_.offered() ? "offered" : "none");
  if (options_.farm) line += " lost_ranks=" + std::to_string(stats.lostRanks.size());
  line += " error=" + std::string(loadError().empty() ? "0" : "1");
  line += " scene=" + describeScene(scenePath());
  return line;
}

}  // namespace rayview
