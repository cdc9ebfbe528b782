// The viewer's speed-vs-accuracy logic without a window: the request it measures, the advice, the task.
#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <thread>

#include <gtest/gtest.h>
#include <imgui.h>
#include <imgui_internal.h>

#include "automation_script.h"
#include "file_watch.h"
#include "numbered_file.h"
#include "recent_files.h"
#include "rayview/scene_loader.h"
#include "scene_edits.h"
#include "scene_session.h"
#include "script_runner.h"
#include "support/image_compare.h"
#include "tradeoff_advice.h"
#include "tradeoff_task.h"
#include "viewer_fixtures.h"

namespace rayview {
namespace {

using namespace viewer_testing;

// ------------------------------------------------------------------------------------- speed vs accuracy

TEST(Tradeoff, TheMeasuredSceneHasTheMeshesAndTheCommittedEdits) {
  SceneSession session(loadParts(), RenderSettings{});
  session.edits().maxRayDepth = 5;
  session.edits().camera.position = glm::dvec3(1.0, 2.0, 3.0);
  session.edits().lights.of<PointLight>()[0].intensity = Color(1.0f, 2.0f, 3.0f);
  const int red = findMaterial(session.edits(), "red");
  session.edits().materials[static_cast<std::size_t>(red)].diffuse = Color(0.0f, 1.0f, 0.0f);
  std::string problem;
  ASSERT_NE(session.commit(problem), nullptr);
  session.edits().maxRayDepth = 7;  // not committed yet: not measured

  const TradeoffRequest request = tradeoffRequestFor(session, 0.25);
  EXPECT_EQ(request.geometry->triangles.size(), session.loaded().triangles.size());
  EXPECT_EQ(request.geometry.get(), session.geometry().source.get());  // shared, never copied
  EXPECT_FALSE(request.geometry->triangles.empty());
  const SceneParameters* scene = &request.parameters;
  EXPECT_EQ(scene->maxRayDepth, 5);
  EXPECT_EQ(scene->camera.position, glm::dvec3(1.0, 2.0, 3.0));
  EXPECT_EQ(scene->lights.of<PointLight>()[0].intensity, Color(1.0f, 2.0f, 3.0f));
  EXPECT_EQ(scene->materials[static_cast<std::size_t>(red)].diffuse, Color(0.0f, 1.0f, 0.0f));
  EXPECT_EQ(session.loaded().maxRayDepth, 2);  // the loaded scene is untouched
  EXPECT_NE(session.loaded().camera.position, glm::dvec3(1.0, 2.0, 3.0));
}

TEST(Tradeoff, EveryKnobIsVariedFromTheSettingsOnScreen) {
  SceneSession session(loadParts(), RenderSettings{});
  session.edits().maxRayDepth = 1;
  session.settings().lightSamples = 8;
  session.settings().pixelSamples = 4;
  session.settings().triangularLightModel = TriangularLightModel::Directional;
  session.settings().secondaryRayStart = SecondaryRayStart::ExcludeHitTriangle;
  std::string problem;
  ASSERT_NE(session.commit(problem), nullptr) << problem;
  session.settings().pixelSamples = 16;  // not committed yet: not measured

  const TradeoffRequest request = tradeoffRequestFor(session, 0.25);
  EXPECT_EQ(request.options.baseline, session.committedSettings());
  EXPECT_EQ(request.options.baseline.pixelSamples, 4);
  EXPECT_EQ(request.options.baseline.lightSamples, 8);
  // Each row differs from what is on screen in its own knob only; the others are the user's.
  const std::vector<KnobSetting> rows = enumerateKnobSettings(request.parameters, request.options);
  for (const KnobSetting& k : rows) {
    if (k.knob == TradeoffKnob::BestImage) continue;
    const std::string row = std::string(toString(k.knob)) + " " + k.label;
    EXPECT_TRUE(k.knob == TradeoffKnob::Depth || k.depth == 1) << row;
    EXPECT_TRUE(k.knob == TradeoffKnob::PixelSamples || k.settings.pixelSamples == 4) << row;
    EXPECT_TRUE(k.knob == TradeoffKnob::LightSamples || k.settings.lightSamples == 8) << row;
    EXPECT_TRUE(k.knob == TradeoffKnob::Accel || k.settings.accel == session.committedSettings().accel) << row;
    EXPECT_EQ(k.settings.triangularLightModel, TriangularLightModel::Directional) << row;
    EXPECT_EQ(k.settings.secondaryRayStart, SecondaryRayStart::ExcludeHitTriangle) << row;
  }
}

TEST(Tradeoff, ScaledSideRoundsAsTheMeasurementDoes) {
  EXPECT_EQ(scaledSide(480, 0.25), 120);
  EXPECT_EQ(scaledSide(300, 0.25), 75);
  EXPECT_EQ(scaledSide(3, 0.25), 1);
  EXPECT_EQ(scaledSide(301, 0.5), 151);
}

TradeoffPoint point(TradeoffKnob knob, const std::string& label, double ms, double pctOff, int stride = 1) {
  TradeoffPoint p;
  p.setting.knob = knob;
  p.setting.label = label;
  p.setting.stride = stride;
  if (knob == TradeoffKnob::LightSamples) p.setting.settings.lightSamples = std::stoi(label);
  p.timeMs = ms;
  p.error.pctOffByMoreThan1 = pctOff;
  return p;
}

TEST(Tradeoff, AdviceNamesTheFastestSettingCloseToTheBestImage) {
  TradeoffReport r;
  EXPECT_EQ(tradeoffAdvice(r), "");
  r.points = {point(TradeoffKnob::BestImage, "best", 300.0, 0.0), point(TradeoffKnob::Preview, "1/2", 1.0, 30.0, 2),
              point(TradeoffKnob::Preview, "1", 2.0, 12.0), point(TradeoffKnob::LightSamples, "32", 40.0, 0.3),
              point(TradeoffKnob::LightSamples, "64", 80.0, 0.0)};
  std::string advice = tradeoffAdvice(r);
  EXPECT_NE(advice.find(": Light samples 32, 40.0 ms"), std::string::npos) << advice;  // the panel's words
  EXPECT_NE(advice.find("the best image: 300.0 ms"), std::string::npos) << advice;
  r.points[2].error.pctOffByMoreThan1 = 0.5;  // the user's settings are close enough
  advice = tradeoffAdvice(r);
  EXPECT_EQ(advice.rfind("Your settings are enough: 2.0 ms", 0), 0u) << advice;
  r.points = {point(TradeoffKnob::BestImage, "best", 300.0, 0.0), point(TradeoffKnob::Preview, "1", 2.0, 12.0)};
  EXPECT_EQ(tradeoffAdvice(r).rfind("No setting but the best image", 0), 0u) << tradeoffAdvice(r);
}

// The rows the viewer would measure for the session, with made-up figures: what Apply works on.
TradeoffReport rowsFor(const SceneSession& session) {
  const TradeoffRequest request = tradeoffRequestFor(session, 0.25);
  TradeoffReport report;
  for (const KnobSetting& k : enumerateKnobSettings(request.parameters, request.options)) {
    TradeoffPoint& p = report.points.emplace_back();
    p.setting = k;
  }
  return report;
}

TEST(Tradeoff, ApplyingARowSetsItsKnobAsTheRenderPanelDoesUndoably) {
  SceneSession session(loadParts(), RenderSettings{});
  const TradeoffReport report = rowsFor(session);
  const TradeoffPoint* sixteen = findTradeoffRow(report, lightSamplesKnob(), 16);
  ASSERT_NE(sixteen, nullptr);
  EXPECT_EQ(describeRow(sixteen->setting), "Light samples 16");
  ASSERT_TRUE(applyKnobSetting(session, sixteen->setting));
  EXPECT_EQ(session.settings().lightSamples, 16);
  // The edit the Render panel's widget would make: the commit restarts the render, as one undo step.
  std::string problem;
  EXPECT_NE(session.commit(problem), nullptr) << problem;
  EXPECT_EQ(session.committedSettings().lightSamples, 16);
  EXPECT_EQ(session.history().undoSteps(), 1u);
  ASSERT_TRUE(session.undo());
  EXPECT_EQ(session.settings().lightSamples, 1);

  ASSERT_TRUE(applyKnobSetting(session, findTradeoffRow(report, depthKnob(), 0)->setting));
  EXPECT_EQ(session.edits().maxRayDepth, 0);  // the depth lives in the scene's parameters
  ASSERT_TRUE(applyKnobSetting(session, findTradeoffRow(report, pixelSamplesKnob(), 4)->setting));
  EXPECT_EQ(session.settings().pixelSamples, 4);
  EXPECT_NE(session.commit(problem), nullptr);
  EXPECT_EQ(session.committedEdits().maxRayDepth, 0);
  EXPECT_EQ(session.committedSettings().pixelSamples, 4);
  if (availableAccel(AccelKind::Embree) == AccelKind::Embree) {
    const TradeoffPoint* embree = findTradeoffRow(report, accelKnob(), static_cast<int>(AccelKind::Embree));
    ASSERT_NE(embree, nullptr);
    ASSERT_TRUE(applyKnobSetting(session, embree->setting));
    EXPECT_TRUE(session.needsRebuild());  // the traversal: the BVH is built again, as from the Render panel
  }
}

TEST(Tradeoff, TheBestImageAndThePreviewLevelsAreNotSettingsToApply) {
  SceneSession session(loadParts(), RenderSettings{});
  const TradeoffReport report = rowsFor(session);
  for (const TradeoffPoint& p : report.points) {
    if (p.setting.knob != TradeoffKnob::BestImage && p.setting.knob != TradeoffKnob::Preview) continue;
    EXPECT_FALSE(applyKnobSetting(session, p.setting)) << describeRow(p.setting);
  }
  EXPECT_FALSE(session.hasPendingEdits());
  EXPECT_EQ(findTradeoffRow(report, lightSamplesKnob(), 3), nullptr);  // not measured
}

TEST(Tradeoff, TheAdviceSuggestsARenderSettingNeverAPreviewLevel) {
  TradeoffReport r;
  r.points = {point(TradeoffKnob::BestImage, "", 300.0, 0.0), point(TradeoffKnob::Preview, "1/2", 1.0, 0.5, 2),
              point(TradeoffKnob::Preview, "1", 2.0, 12.0), point(TradeoffKnob::LightSamples, "32", 40.0, 0.3)};
  // The 1/2 preview is fastest and close enough, but a user cannot choose it: 32 light samples are suggested.
  ASSERT_NE(tradeoffSuggestion(r), nullptr);
  EXPECT_EQ(tradeoffSuggestion(r), &r.points[3]);
  r.points[2].error.pctOffByMoreThan1 = 0.5;  // the user's settings are enough: nothing to apply
  EXPECT_EQ(tradeoffSuggestion(r), nullptr);
  r.points[2].error.pctOffByMoreThan1 = 12.0;
  r.points[3].error.pctOffByMoreThan1 = 3.0;  // nothing close enough
  EXPECT_EQ(tradeoffSuggestion(r), nullptr);
}

TradeoffRequest smallRequest(SceneSession& session) {
  TradeoffRequest request = tradeoffRequestFor(session, 0.1);
  request.options.limit(lightSamplesKnob(), 4, 4);
  request.options.timedRuns = 1;
  request.options.fastTimedRuns = 1;
  request.options.slowedRetries = 0;
  request.plotWidth = 480;
  request.plotHeight = 300;
  return request;
}

template <typename Done>
bool waitUntil(Done done, std::chrono::seconds limit = std::chrono::seconds(60)) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

TEST(Tradeoff, TheTaskMeasuresOnItsOwnThreadAndPlots) {
  SceneSession session(loadParts(), RenderSettings{});
  TradeoffTask task(2);
  std::atomic<int> finished{0};
  task.setFinishedListener([&] { ++finished; });
  const std::uint64_t id = task.start(smallRequest(session));
  std::optional<TradeoffResult> result;
  ASSERT_TRUE(waitUntil([&] { return (result = task.takeResult()).has_value(); }));
  EXPECT_EQ(result->id, id);
  ASSERT_TRUE(result->ok()) << result->error;
  EXPECT_GE(result->report.points.size(), 5u);
  EXPECT_EQ(result->report.width, 48);  // 480 x 300 at 0.1
  EXPECT_EQ(result->report.height, 30);
  EXPECT_EQ(result->plot.width, 480);
  EXPECT_EQ(result->plot.height, 300);
  EXPECT_TRUE(waitUntil([&] { return finished.load() == 1; }));  // called just after the result is ready
  EXPECT_FALSE(task.status().busy);
  EXPECT_FALSE(task.takeResult().has_value());  // once
}

TEST(Tradeoff, CancelStopsTheMeasurementAndANewerRequestWins) {
  SceneSession session(loadParts(), RenderSettings{});
  TradeoffTask task(2);
  TradeoffRequest slow = smallRequest(session);
  slow.options.resolutionScale = 1.0;
  slow.options.limit(lightSamplesKnob(), 256, 256);
  slow.options.timedRuns = 3;
  task.start(slow);
  ASSERT_TRUE(waitUntil([&] { return task.status().progress.rendersPlanned > 0; }));  // measuring
  // Stopped within the render in flight: no later render of the plan is started (the wait is a watchdog only).
  const TradeoffProgress atCancel = task.status().progress;
  task.cancel();
  ASSERT_TRUE(waitUntil([&] { return !task.status().busy; }, std::chrono::seconds(60)));
  EXPECT_LE(task.status().progress.rendersDone, atCancel.rendersDone + 1);
  EXPECT_LT(atCancel.rendersDone, atCancel.rendersPlanned);
  if (std::optional<TradeoffResult> result = task.takeResult()) {
    EXPECT_TRUE(result->cancelled);
  }

  // A request superseded by a newer one never reports; the newer one does.
  task.start(slow);
  const std::uint64_t newer = task.start(smallRequest(session));
  std::optional<TradeoffResult> result;
  ASSERT_TRUE(waitUntil([&] { return (result = task.takeResult()).has_value(); }));
  EXPECT_EQ(result->id, newer);
  EXPECT_TRUE(result->ok()) << result->error;
}

}  // namespace
}  // namespace rayview
