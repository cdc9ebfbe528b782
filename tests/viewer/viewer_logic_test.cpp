// The viewer's logic without a window: scripts, edits and restarts, numbered saves, file watching, recent files.
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
#include "panels.h"
#include "save_controller.h"
#include "recent_files.h"
#include "rayview/scene_loader.h"
#include "scene_edits.h"
#include "rayview/view_camera.h"
#include "scene_session.h"
#include "script_runner.h"
#include "support/image_compare.h"
#include "tradeoff_task.h"
#include "viewer_fixtures.h"
#include "widgets.h"

namespace rayview {
namespace {

using namespace viewer_testing;

// ---------------------------------------------------------------------------------------------- scripts

TEST(AutomationScript, ParsesEveryCommandWithItsArguments) {
  const Script s = parseScript(
      "# a comment\n"
      "\n"
      "wait-final\n"
      "wait-final 5\n"
      "set material \"my red\" diffuse 0.1 0.2 +0.3\n"
      "set light sun position 1 2 3\n"
      "set depth 3\n"
      "set tri-light directional\n"
      "camera orbit 10 -5\n"
      "camera resolution 320 200\n"
      "open /tmp/a dir/scene #1.xml\n"
      "expect-error scene.xml:12: error\n"
      "save-frame\n"
      "quit 3\n",
      "t.rvs");
  ASSERT_EQ(s.commands.size(), 12u);
  EXPECT_EQ(s.commands[0].line, 3);
  EXPECT_TRUE(s.commands[0].numbers.empty());
  EXPECT_EQ(s.commands[1].numbers, std::vector<double>{5.0});
  EXPECT_EQ(s.commands[2].args, (std::vector<std::string>{"material", "my red", "diffuse"}));
  EXPECT_EQ(s.commands[2].numbers, (std::vector<double>{0.1, 0.2, 0.3}));
  EXPECT_EQ(s.commands[5].args, (std::vector<std::string>{"tri-light", "directional"}));
  EXPECT_EQ(s.commands[6].numbers, (std::vector<double>{10.0, -5.0}));
  EXPECT_EQ(s.commands[8].args, std::vector<std::string>{"/tmp/a dir/scene #1.xml"});  // the rest of the line
  EXPECT_EQ(s.commands[9].args, std::vector<std::string>{"scene.xml:12: error"});
  EXPECT_TRUE(s.commands[10].args.empty());
  EXPECT_EQ(s.commands[11].numbers, std::vector<double>{3.0});
}

TEST(AutomationScript, MistakesNameTheFileAndLine) {
  auto errorOf = [](const std::string& text) {
    try {
      parseScript(text, "t.rvs");
    } catch (const ScriptError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(errorOf("wait-final\nfly away\n").rfind("t.rvs:2: unknown command 'fly'", 0), 0u) << errorOf("fly");
  EXPECT_NE(errorOf("set material red diffuse 1 2\n").find("t.rvs:1: usage: set material"), std::string::npos);
  EXPECT_NE(errorOf("set depth 1.5\n").find("whole numbers"), std::string::npos);
  EXPECT_NE(errorOf("set depth x\n").find("expects a number, not 'x'"), std::string::npos);
  EXPECT_NE(errorOf("camera resolution 0 10\n").find("t.rvs:1:"), std::string::npos);
  EXPECT_NE(errorOf("set tri-light sun\n").find("area|directional"), std::string::npos);
  EXPECT_NE(errorOf("open\n").find("needs a path"), std::string::npos);
  EXPECT_NE(errorOf("wait-final 0\n").find("positive"), std::string::npos);
  EXPECT_NE(errorOf("print-state now\n").find("takes no arguments"), std::string::npos);
  EXPECT_NE(errorOf("set light \"sun position 1 2 3\n").find("unterminated quote"), std::string::npos);
  EXPECT_NE(errorOf("measure-tradeoff 0\n").find("t.rvs:1: the resolution scale"), std::string::npos);
  EXPECT_NE(errorOf("measure-tradeoff 1.5\n").find("at most 1"), std::string::npos);
  EXPECT_NE(errorOf("measure-tradeoff 0.5 -1\n").find("positive timeout"), std::string::npos);
  EXPECT_NE(errorOf("measure-tradeoff 0.5 10 3\n").find("usage: measure-tradeoff"), std::string::npos);
}

TEST(AutomationScript, MeasureTradeoffFillsInItsDefaults) {
  const Script s = parseScript("measure-tradeoff\nmeasure-tradeoff 0.5\nmeasure-tradeoff 1 30\n", "t.rvs");
  ASSERT_EQ(s.commands.size(), 3u);
  EXPECT_EQ(s.commands[0].numbers, (std::vector<double>{kDefaultTradeoffScale, kDefaultTradeoffSeconds}));
  EXPECT_EQ(s.commands[1].numbers, (std::vector<double>{0.5, kDefaultTradeoffSeconds}));
  EXPECT_EQ(s.commands[2].numbers, (std::vector<double>{1.0, 30.0}));
}

TEST(ScriptRunner, WaitsForTheFinalPassThenRunsOneCommandPerFrame) {
  SceneSession session(loadParts(), RenderSettings{});
  FakeHost host(&session);
  ScriptRunner runner(parseScript("wait-final\nset material red diffuse 0 1 0\nsave-frame out.png\nquit 4\n", "t"));
  host.frame(runner);
  host.frame(runner);
  EXPECT_EQ(host.savedFrame, "-");  // still waiting
  host.final = true;
  host.frame(runner);  // wait over, the edit runs
  EXPECT_EQ(session.edits().materials[static_cast<std::size_t>(findMaterial(session.edits(), "red"))].diffuse,
            Color(0, 1, 0));
  EXPECT_EQ(host.savedFrame, "-");
  host.final = false;  // the edit restarted the render
  host.frame(runner);
  host.frame(runner);
  EXPECT_EQ(host.savedFrame, "-");  // save-frame saves the final pass, never a coarse one
  host.final = true;
  host.frame(runner);  // saved, and the next command runs
  EXPECT_EQ(host.savedFrame, "out.png");
  EXPECT_EQ(host.exitCode, 4);
  EXPECT_FALSE(runner.running());
  EXPECT_FALSE(runner.failed());
}

TEST(ScriptRunner, AFailedOpenMustBeExpected) {
  SceneSession session(loadParts(), RenderSettings{});
  {
    FakeHost host(&session);
    host.error = "broken.xml:7: error: the file ends inside <vertexdata>";
    ScriptRunner runner(parseScript("open broken.xml\nexpect-error broken.xml:7\nquit\n", "t"));
    for (int i = 0; i < 6; ++i) host.frame(runner);
    EXPECT_EQ(host.opened, "broken.xml");
    EXPECT_FALSE(runner.failed()) << runner.failure();
    EXPECT_EQ(host.exitCode, 0);
  }
  {
    FakeHost host(&session);
    host.error = "broken.xml:7: error: the file ends inside <vertexdata>";
    ScriptRunner runner(parseScript("open broken.xml\nquit\n", "t"));
    for (int i = 0; i < 6; ++i) host.frame(runner);
    EXPECT_TRUE(runner.failed());
    EXPECT_NE(runner.failure().find("t:1: open failed: broken.xml:7"), std::string::npos) << runner.failure();
  }
  {
    FakeHost host(&session);
    host.error = "other.xml:1: error: something else";
    ScriptRunner runner(parseScript("open broken.xml\nexpect-error broken.xml:7\n", "t"));
    for (int i = 0; i < 6; ++i) host.frame(runner);
    EXPECT_TRUE(runner.failed());
    EXPECT_NE(runner.failure().find("t:2: expected an error containing 'broken.xml:7'"), std::string::npos);
  }
}

TEST(ScriptRunner, UnknownIdsFailWithTheKnownOnes) {
  SceneSession session(loadParts(), RenderSettings{});
  FakeHost host(&session);
  ScriptRunner runner(parseScript("set light moon position 1 2 3\n", "t"));
  host.frame(runner);
  ASSERT_TRUE(runner.failed());
  EXPECT_NE(runner.failure().find("point lights: sun; triangular lights: strip"), std::string::npos) << runner.failure();
}

TEST(ScriptRunner, MeasureTradeoffWaitsThenPrintsThePointCount) {
  FakeHost host(nullptr);
  ScriptRunner runner(parseScript("measure-tradeoff 0.5\nquit 7\n", "t"));
  host.frame(runner);
  EXPECT_EQ(host.measuredScale, 0.5);
  host.frame(runner);
  host.frame(runner);
  EXPECT_EQ(host.exitCode, -1);  // still measuring
  host.tradeoff = TradeoffState{false, 17, ""};
  ::testing::internal::CaptureStdout();
  host.frame(runner);  // the wait is over: the line, then the next command
  EXPECT_EQ(::testing::internal::GetCapturedStdout(), "tradeoff 17 points\n");
  EXPECT_EQ(host.exitCode, 7);
  EXPECT_FALSE(runner.failed());
}

TEST(AutomationScript, TradeoffApplyNamesAMeasuredKnobAndItsValueOrTheAdvice) {
  const Script script = parseScript("tradeoff-apply light-samples 16\ntradeoff-apply accel reference\n"
                                    "tradeoff-apply advice\n", "t");
  ASSERT_EQ(script.commands.size(), 3u);
  EXPECT_EQ(script.commands[0].args, (std::vector<std::string>{"light-samples", "16"}));
  EXPECT_EQ(script.commands[0].numbers, (std::vector<double>{16.0}));
  EXPECT_EQ(script.commands[1].numbers, (std::vector<double>{static_cast<double>(AccelKind::Reference)}));
  EXPECT_EQ(script.commands[2].args, (std::vector<std::string>{"advice"}));
  for (const char* bad : {"tradeoff-apply", "tradeoff-apply ray-start offset", "tradeoff-apply preview 4",
                          "tradeoff-apply light-samples", "tradeoff-apply light-samples many",
                          "tradeoff-apply accel bvh", "tradeoff-apply advice now"}) {
    EXPECT_THROW(parseScript(bad, "t"), ScriptError) << bad;
  }
  try {
    parseScript("tradeoff-apply ray-start offset\n", "t");
  } catch (const ScriptError& error) {
    EXPECT_NE(std::string(error.what()).find("t:1: usage: tradeoff-apply advice, or tradeoff-apply "
                                             "depth|light-samples|accel|samples VALUE"),
              std::string::npos)
        << error.what();
  }
}

TEST(ScriptRunner, TradeoffApplyAsksTheViewerAndFailsWithItsReason) {
  FakeHost host(nullptr);
  ScriptRunner runner(parseScript("tradeoff-apply samples 4\ntradeoff-apply advice\n", "t"));
  host.frame(runner);
  EXPECT_EQ(host.applied, "samples 4");
  EXPECT_FALSE(runner.failed());
  host.applyError = "the advice suggests no setting";
  host.frame(runner);
  EXPECT_EQ(host.applied, "advice");
  ASSERT_TRUE(runner.failed());
  EXPECT_EQ(runner.failure(), "t:2: tradeoff-apply: the advice suggests no setting");
}

TEST(ScriptRunner, MeasureTradeoffFailsWhenCancelledOrLate) {
  {
    FakeHost host(nullptr);
    ScriptRunner runner(parseScript("measure-tradeoff\n", "t"));
    host.frame(runner);
    host.tradeoff = TradeoffState{false, 0, "cancelled: the scene was edited"};
    host.frame(runner);
    ASSERT_TRUE(runner.failed());
    EXPECT_NE(runner.failure().find("t:1: measure-tradeoff: cancelled: the scene was edited"), std::string::npos)
        << runner.failure();
  }
  {
    FakeHost host(nullptr);
    ScriptRunner runner(parseScript("measure-tradeoff 0.25 0.05\n", "t"));
    host.frame(runner);
    std::this_thread::sleep_for(std::chrono::milliseconds(80));
    host.frame(runner);
    ASSERT_TRUE(runner.failed());
    EXPECT_NE(runner.failure().find("did not finish within"), std::string::npos) << runner.failure();
    EXPECT_EQ(host.tradeoff.error, "cancelled");  // the runner stopped it
  }
}

TEST(ScriptRunner, WaitFinalTimesOut) {
  FakeHost host(nullptr);
  ScriptRunner runner(parseScript("wait-final 0.05\n", "t"));
  host.frame(runner);
  std::this_thread::sleep_for(std::chrono::milliseconds(80));
  host.frame(runner);
  ASSERT_TRUE(runner.failed());
  EXPECT_NE(runner.failure().find("no final pass within"), std::string::npos);
}

// ------------------------------------------------------------------------------------ edits and restarts

TEST(SceneEdits, ClassifiesWhatAChangeCosts) {
  const Scene scene = loadSceneFile(kViewerScene).scene;
  const SceneParameters before = scene.parameters();
  const RenderSettings settings;
  EXPECT_EQ(classifyEdit(before, settings, before, settings), EditEffect::None);
  SceneParameters camera = before;
  camera.camera.position.x += 1e-9;
  EXPECT_EQ(classifyEdit(before, settings, camera, settings), EditEffect::Restart);
  SceneParameters material = before;
  material.materials[1].phongExponent += 1.0f;
  EXPECT_EQ(classifyEdit(before, settings, material, settings), EditEffect::Restart);
  SceneParameters light = before;
  light.lights.of<TriangularLight>()[0].vertex2.z = 0.5;
  EXPECT_EQ(classifyEdit(before, settings, light, settings), EditEffect::Restart);
  RenderSettings samples = settings;
  samples.lightSamples = 16;
  EXPECT_EQ(classifyEdit(before, settings, before, samples), EditEffect::Restart);
  RenderSettings accel = settings;
  accel.accel = AccelKind::Reference;
  EXPECT_EQ(classifyEdit(before, settings, before, accel), EditEffect::Rebuild);
}

TEST(SceneEdits, RefusesWhatCannotBeRendered) {
  const SceneParameters good = loadSceneFile(kViewerScene).scene.parameters();
  EXPECT_EQ(editProblem(good, RenderSettings{}), "");
  SceneParameters e = good;
  e.camera.gaze = glm::dvec3(0.0);
  EXPECT_NE(editProblem(e, RenderSettings{}).find("camera"), std::string::npos);
  e = good;
  e.camera.width = 100000;
  EXPECT_NE(editProblem(e, RenderSettings{}).find("too large"), std::string::npos);
  e = good;
  e.materials[0].diffuse.x = std::numeric_limits<float>::infinity();
  EXPECT_NE(editProblem(e, RenderSettings{}).find("material floor"), std::string::npos);
}

// The window view: the area's size restarts the render at that resolution; it is no edit (no undo step, nothing
// unsaved), saves still get the file's image, and a click picks through the window view's own pixels.
TEST(SceneSession, TheWindowViewRendersTheAreaAndSavesTheFile) {
  SceneSession session(loadParts(), RenderSettings{});
  std::string problem;
  const Camera file = session.committedEdits().camera;  // 480x300
  session.setViewport(std::pair{880, 800});
  EXPECT_TRUE(session.hasPendingEdits()) << "the image on screen is not the one asked for yet";
  auto source = session.commit(problem);
  ASSERT_NE(source, nullptr);
  EXPECT_EQ(source->width(), 880);
  EXPECT_EQ(source->height(), 800);
  EXPECT_EQ(session.commitCount(), 0u) << "not an edit";
  EXPECT_EQ(session.history().undoSteps(), 0u);
  EXPECT_FALSE(session.unsaved());
  EXPECT_EQ(session.commit(problem), nullptr) << "the same size again: nothing to restart";
  EXPECT_EQ(session.fileSource()->width(), file.width);
  EXPECT_EQ(session.fileSource()->height(), file.height);
  EXPECT_EQ(session.renderedCamera(), windowViewCamera(file, 880, 800));

  // The centre of the window view is the centre of the file's view: the same thing is picked.
  const auto byFile = session.pick(file.width / 2, file.height / 2);
  const auto byWindow = session.pickRendered(440, 400);
  ASSERT_EQ(byFile.has_value(), byWindow.has_value());
  if (byFile) {
    EXPECT_EQ(byFile->mesh, byWindow->mesh);
  }

  session.setViewport(std::nullopt);  // the image view
  source = session.commit(problem);
  ASSERT_NE(source, nullptr);
  EXPECT_EQ(source->width(), file.width);
  EXPECT_EQ(source->height(), file.height);
}

TEST(SceneSession, CommitRestartsOnlyOnChangeAndKeepsMeshesOutOfSnapshots) {
  SceneSession session(loadParts(), RenderSettings{});
  std::string problem;
  EXPECT_EQ(session.commit(problem), nullptr);
  session.navigate([](OrbitCamera& o) { o.orbit(0.2, 0.1); });
  EXPECT_TRUE(session.hasPendingEdits());
  auto source = session.commit(problem);
  ASSERT_NE(source, nullptr);
  EXPECT_EQ(problem, "");
  EXPECT_FALSE(session.hasPendingEdits());
  EXPECT_EQ(session.commit(problem), nullptr);
  EXPECT_EQ(session.commitCount(), 1u);
  // An invalid edit is reported and not rendered.
  session.edits().camera.nearDistance = 0.0;
  EXPECT_EQ(session.commit(problem), nullptr);
  EXPECT_NE(problem, "");
  session.edits().camera.nearDistance = 1.0;  // back to what is rendered: nothing to restart
  EXPECT_EQ(session.commit(problem), nullptr);
  EXPECT_EQ(problem, "");
  session.edits().camera.nearDistance = 2.0;
  EXPECT_NE(session.commit(problem), nullptr);
  // What is saved has the meshes and the edits.
  const Scene edited = session.editedScene();
  EXPECT_EQ(edited.triangles.size(), session.loaded().triangles.size());
  EXPECT_EQ(edited.camera.position, session.edits().camera.position);
}

TEST(SceneSession, DepthOverrideBecomesTheScenesDepth) {
  const KnobAssignment depth{&depthKnob(), 5};  // --depth 5
  SceneSession session(loadParts(), RenderSettings{}, {&depth, 1});
  EXPECT_EQ(session.edits().maxRayDepth, 5);
  EXPECT_EQ(session.committedEdits().maxRayDepth, 5);
  EXPECT_EQ(session.editedScene().maxRayDepth, 5);
}

TEST(SceneSession, ResolutionEditsKeepTheNearPlanesAspect) {
  SceneSession session(loadParts(), RenderSettings{});  // near plane 1.28 x 0.8, image 480 x 300
  session.setResolutionKeepingAspect(800, 300, true);
  EXPECT_EQ(session.edits().camera.width, 800);
  EXPECT_EQ(session.edits().camera.height, 500);
  session.setResolutionKeepingAspect(800, 100, false);
  EXPECT_EQ(session.edits().camera.width, 160);
  EXPECT_EQ(session.edits().camera.height, 100);
}

// ------------------------------------------------------------------------------------------ saving

TEST(NumberedFile, NeverOverwritesAndLeavesNoTemporary) {
  const fs::path directory = freshDirectory("numbered");
  const std::string scene = (directory / "room.xml").string();
  writeText(directory / "room_001.png", "someone else's file");
  Image image(4, 2);
  image.pixel(1, 1)[0] = 200;
  const fs::path first = saveFrameNumbered(image, scene);
  const fs::path second = saveFrameNumbered(image, scene);
  EXPECT_EQ(first.filename(), "room_002.png");
  EXPECT_EQ(second.filename(), "room_003.png");
  std::ifstream untouched(directory / "room_001.png");
  std::string text;
  std::getline(untouched, text);
  EXPECT_EQ(text, "someone else's file");
  EXPECT_EQ(readImageFile(second).rgb, image.rgb);
  int files = 0;
  for (const auto& entry : fs::directory_iterator(directory)) {
    ++files;
    EXPECT_EQ(entry.path().filename().string().find(".saving"), std::string::npos) << entry.path();
  }
  EXPECT_EQ(files, 3);
}

TEST(NumberedFile, TheDefaultSceneSavesInTheWorkingDirectory) {
  EXPECT_EQ(numberedFileBase(""), fs::current_path() / "default");
  EXPECT_EQ(numberedFileBase("/a/b/scene.xml"), fs::path("/a/b/scene"));
}

// ------------------------------------------------------------------------------ watching and recent files

TEST(FileWatch, SeesAChangeOnceAndNoMoreOftenThanItsInterval) {
  const fs::path directory = freshDirectory("watch");
  const fs::path file = directory / "scene.xml";
  writeText(file, "one");
  FileWatch watch;
  watch.watch(file);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_FALSE(watch.changed(start + kFileWatchInterval));
  writeText(file, "two, longer");
  EXPECT_FALSE(watch.changed(start + kFileWatchInterval + std::chrono::milliseconds(1)));  // too soon to look
  EXPECT_TRUE(watch.changed(start + 2 * kFileWatchInterval + std::chrono::milliseconds(2)));
  EXPECT_FALSE(watch.changed(start + 4 * kFileWatchInterval));
  fs::remove(file);  // an editor replacing the file: a missing file is no change
  EXPECT_FALSE(watch.changed(start + 6 * kFileWatchInterval));
  EXPECT_GE(watch.secondsUntilNextLook(start + 6 * kFileWatchInterval), 0.0);
}

TEST(RecentFiles, NewestFirstWithoutDuplicatesAndPersisted) {
  const fs::path directory = freshDirectory("recent");
  const fs::path storage = directory / "config/rayview/recent.txt";
  {
    RecentFiles recent(storage);
    EXPECT_TRUE(recent.paths().empty());
    for (std::size_t i = 0; i < kMaxRecentFiles + 3; ++i) EXPECT_TRUE(recent.add("/s/" + std::to_string(i) + ".xml"));
    EXPECT_TRUE(recent.add("/s/5.xml"));
    EXPECT_EQ(recent.paths().size(), kMaxRecentFiles);
    EXPECT_EQ(recent.paths().front(), "/s/5.xml");
  }
  RecentFiles again(storage);
  ASSERT_EQ(again.paths().size(), kMaxRecentFiles);
  EXPECT_EQ(again.paths()[0], "/s/5.xml");
  EXPECT_EQ(again.paths()[1], "/s/" + std::to_string(kMaxRecentFiles + 2) + ".xml");
}

// ImGui without a window: frames drawn into nothing, the mouse put where a test wants it.
class HeadlessImGui {
 public:
  HeadlessImGui() {
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;
    io.DisplaySize = ImVec2(800, 600);
    io.DeltaTime = 1.0f / 60.0f;
    unsigned char* pixels = nullptr;
    int width = 0, height = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &width, &height);
  }
  ~HeadlessImGui() { ImGui::DestroyContext(); }
  template <typename Draw>
  void frame(ImVec2 mouse, Draw&& draw) {
    ImGui::GetIO().MousePos = mouse;
    ImGui::NewFrame();
    ImGui::SetNextWindowPos(ImVec2(0, 0));
    ImGui::SetNextWindowSize(ImVec2(400, 400));
    ImGui::Begin("panel");
    draw();
    ImGui::End();
    ImGui::Render();
  }
  static bool tooltipShown() {
    const ImGuiWindow* tooltip = ImGui::FindWindowByName("##Tooltip_00");
    return tooltip && tooltip->Active;
  }
};

// The light model and the samples once showed no tooltip over their fields. Each knob's help is its tooltip.
TEST(RenderPanel, KnobTooltipsShowOverTheirFields) {
  // Light samples twice: enabled (area model), and greyed out (directional), where the tooltip says why.
  for (const char* name : {"light-samples", "tri-light", "depth", "light-samples"}) {
    static int round = 0;
    HeadlessImGui imgui;
    RenderSettings settings;
    if (round++ == 3) settings.triangularLightModel = TriangularLightModel::Directional;
    SceneSession session(loadParts(), settings);
    const Knob& knob = *findKnob(name);
    ImVec2 fieldMin;
    const auto draw = [&] {
      editKnob(knob, session.edits(), session.settings());
      fieldMin = ImGui::GetItemRectMin();
    };
    imgui.frame(ImVec2(-100, -100), draw);
    EXPECT_FALSE(HeadlessImGui::tooltipShown()) << name;
    // Over the left end of the field (not the label): the text box, or the combo's preview.
    for (int i = 0; i < 3; ++i) imgui.frame(ImVec2(fieldMin.x + 8, fieldMin.y + 6), draw);
    EXPECT_TRUE(HeadlessImGui::tooltipShown()) << name << ": no tooltip over the field";
  }
}

// The traversal tooltip (the longest help) stays inside a narrow window even when the field is at its right edge.
TEST(RenderPanel, TheTraversalTooltipStaysInTheWindow) {
  HeadlessImGui imgui;
  SceneSession session(loadParts(), RenderSettings{});
  const Knob& knob = *findKnob("accel");
  float shown[4] = {0, 0, 0, 0};
  const auto draw = [&] { tooltip(std::string(knob.help) + " (--accel, or `set accel` in scripts)", shown); };
  for (int i = 0; i < 3; ++i) imgui.frame(ImVec2(780, 300), draw);
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  EXPECT_GE(shown[0], 0.0f);
  EXPECT_LE(shown[2], display.x) << "the tooltip runs off the window's right edge";
  EXPECT_LE(shown[3], display.y);
  EXPECT_GT(shown[3] - shown[1], 2.0f * ImGui::GetFontSize()) << "the help is wrapped onto several lines";
}

// The dropdown and the stats name the traversal actually built.
TEST(RenderPanel, TheTraversalNamedIsTheOneBuilt) {
  EXPECT_EQ(traversalBuilt(AccelKind::Embree, AccelKind::Embree, 10), "");
  EXPECT_EQ(traversalBuilt(AccelKind::Embree, AccelKind::Packet, 12), "Embree (packet BVH for small scenes)");
  EXPECT_EQ(traversalBuilt(AccelKind::Embree, AccelKind::Packet, 2'000'000), "Embree (packet BVH: Embree could not be loaded)");
  ViewerStats stats;
  stats.accel = AccelKind::Packet;
  stats.traversal = traversalBuilt(AccelKind::Embree, AccelKind::Packet, 12);
  bool named = false;
  for (const auto& [name, value] : statsText(stats).lines) named |= name == "Traversal" && value == stats.traversal;
  EXPECT_TRUE(named);
}

// Save scene as to another file keeps the title's `*`: the open file did not change. Over the open file it goes.
TEST(SaveController, SaveSceneAsElsewhereKeepsTheOpenFileUnsaved) {
  const fs::path directory = freshDirectory("save_as");
  const fs::path open = directory / "open.xml";
  fs::copy_file(kViewerScene, open);
  SceneSession session(loadParts(), RenderSettings{});
  FilePanelState panel;
  SaveController saves(1, panel);
  session.edits().maxRayDepth += 1;
  std::string problem;
  ASSERT_TRUE(session.commit(problem));
  saves.saveScene(&session, open.string(), (directory / "copy.xml").string());
  EXPECT_FALSE(session.unsaved()) << "the edits are saved somewhere: quitting need not ask";
  EXPECT_TRUE(session.differsFromFile()) << "but the open file still lacks them: the * stays";
  saves.saveScene(&session, open.string(), open.string());
  EXPECT_FALSE(session.differsFromFile());
}

}  // namespace
// A resolution of 0 typed into the Camera panel is refused with a reason, never turned into 1 x 1.
TEST(CameraPanel, ARezeroedResolutionIsRefusedAndSaysWhy) {
  EXPECT_EQ(resolutionRefusal(640, 480), "");
  EXPECT_EQ(resolutionRefusal(1, 1), "");
  EXPECT_NE(resolutionRefusal(0, 480).find("not applied"), std::string::npos);
  EXPECT_NE(resolutionRefusal(640, 0).find("at least 1 pixel"), std::string::npos);
  EXPECT_NE(resolutionRefusal(-3, 480), "");
}

}  // namespace rayview
