// Undo and redo (ui/edit_history, SceneSession), unsaved edits, picking, and their script commands. Part of
// viewer_logic_test.
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "automation_script.h"
#include "edit_history.h"
#include "rayview/scene_loader.h"
#include "scene_session.h"
#include "script_runner.h"
#include "support/image_compare.h"

namespace rayview {
namespace {

const std::filesystem::path kScene = testing::sourceDirectory() / "tests/viewer/viewer_scene.xml";

LoadedSceneParts loadScene(AccelKind accel = AccelKind::Reference) {
  LoadedScene loaded = loadSceneFile(kScene);
  LoadedSceneParts parts;
  parts.scene = std::make_shared<const Scene>(std::move(loaded.scene));
  parts.geometry = prepareGeometry(parts.scene, accel, BvhBuild::Interactive);
  parts.bounds = sceneBounds(*parts.scene);
  parts.accel = accel;
  return parts;
}

EditState depthState(int depth) {
  EditState s;
  s.parameters.maxRayDepth = depth;
  return s;
}

TEST(EditHistory, UndoAndRedoWalkTheCommittedStates) {
  EditHistory history(depthState(1));
  EXPECT_FALSE(history.undo());
  history.record(depthState(2), false);
  history.record(depthState(2), false);  // no change: no step
  history.record(depthState(3), false);
  EXPECT_EQ(history.undoSteps(), 2u);
  EXPECT_EQ(history.undo()->parameters.maxRayDepth, 2);
  EXPECT_EQ(history.undo()->parameters.maxRayDepth, 1);
  EXPECT_FALSE(history.undo());
  EXPECT_EQ(history.current().parameters.maxRayDepth, 1);
  EXPECT_EQ(history.redo()->parameters.maxRayDepth, 2);
  EXPECT_EQ(history.redo()->parameters.maxRayDepth, 3);
  EXPECT_FALSE(history.redo());
}

TEST(EditHistory, ADragIsOneStep) {
  EditHistory history(depthState(1));
  for (int depth = 2; depth <= 10; ++depth) history.record(depthState(depth), true);  // held
  history.endGesture();                                                             // released
  EXPECT_EQ(history.undoSteps(), 1u);
  history.record(depthState(11), true);  // the next drag is a step of its own
  history.record(depthState(12), true);
  history.record(depthState(12), false);
  history.record(depthState(13), false);  // and so is an edit after it
  EXPECT_EQ(history.undoSteps(), 3u);
  EXPECT_EQ(history.undo()->parameters.maxRayDepth, 12);
  EXPECT_EQ(history.undo()->parameters.maxRayDepth, 10);
  EXPECT_EQ(history.undo()->parameters.maxRayDepth, 1);
}

TEST(EditHistory, ANewEditAfterUndoClearsRedo) {
  EditHistory history(depthState(1));
  history.record(depthState(2), false);
  history.record(depthState(3), false);
  history.undo();
  EXPECT_EQ(history.redoSteps(), 1u);
  history.record(depthState(7), false);
  EXPECT_EQ(history.redoSteps(), 0u);
  EXPECT_FALSE(history.redo());
  EXPECT_EQ(history.undo()->parameters.maxRayDepth, 2);
}

TEST(EditHistory, KeepsOnlyTheNewestSteps) {
  EditHistory history(depthState(0), 5);
  for (int depth = 1; depth <= 20; ++depth) history.record(depthState(depth), false);
  EXPECT_EQ(history.undoSteps(), 5u);
  int last = 20;
  while (const auto state = history.undo()) last = state->parameters.maxRayDepth;
  EXPECT_EQ(last, 15);
  EXPECT_EQ(kUndoLimit, 256u);
}

TEST(SceneSessionHistory, UndoRestoresEditsSettingsAndTheCameraAndRestarts) {
  SceneSession session(loadScene(), RenderSettings{});
  std::string problem;
  const SceneParameters original = session.edits();
  session.edits().materials[1].diffuse = Color{0.1f, 0.8f, 0.9f};
  ASSERT_NE(session.commit(problem), nullptr);
  session.settings().lightSamples = 8;
  ASSERT_NE(session.commit(problem), nullptr);
  // A drag: many commits while held, one step.
  session.setGesture(true);
  for (int k = 0; k < 5; ++k) {
    session.navigate([](OrbitCamera& o) { o.orbit(0.05, 0.01); });
    ASSERT_NE(session.commit(problem), nullptr);
  }
  session.setGesture(false);
  EXPECT_EQ(session.history().undoSteps(), 3u);

  ASSERT_TRUE(session.undo());
  EXPECT_EQ(session.edits().camera, original.camera);
  ASSERT_NE(session.commit(problem), nullptr);  // the undone state is rendered
  EXPECT_EQ(session.orbit().camera(), original.camera);  // navigation follows
  ASSERT_TRUE(session.undo());
  EXPECT_EQ(session.settings().lightSamples, RenderSettings{}.lightSamples);
  ASSERT_TRUE(session.undo());
  EXPECT_EQ(session.edits(), original);
  ASSERT_NE(session.commit(problem), nullptr);
  EXPECT_EQ(session.committedEdits(), original);
  EXPECT_FALSE(session.undo());
  EXPECT_EQ(session.history().redoSteps(), 3u);  // committing an undone state is no new step

  ASSERT_TRUE(session.redo());
  EXPECT_EQ(session.edits().materials[1].diffuse, (Color{0.1f, 0.8f, 0.9f}));
}

TEST(SceneSessionHistory, UndoingATraversalChangeAsksForARebuild) {
  SceneSession session(loadScene(AccelKind::Reference), RenderSettings{});
  std::string problem;
  session.settings().accel = AccelKind::Embree;
  session.commit(problem);
  EXPECT_TRUE(session.needsRebuild());
  session.replaceGeometry(loadScene(AccelKind::Embree).geometry, session.settings().accel);
  EXPECT_FALSE(session.needsRebuild());
  ASSERT_TRUE(session.undo());
  session.commit(problem);
  EXPECT_EQ(session.settings().accel, AccelKind::Reference);
  EXPECT_TRUE(session.needsRebuild()) << "the geometry must be built again, as after the edit itself";
}

TEST(SceneSessionHistory, UnsavedUntilSavedOrUndoneBack) {
  SceneSession session(loadScene(), RenderSettings{});
  std::string problem;
  EXPECT_FALSE(session.unsaved());
  session.settings().lightSamples = 4;  // a render setting is not in the file
  session.commit(problem);
  EXPECT_FALSE(session.unsaved());
  session.edits().background = Color{1.0f, 2.0f, 3.0f};
  session.commit(problem);
  EXPECT_TRUE(session.unsaved());
  session.undo();
  session.undo();
  EXPECT_FALSE(session.unsaved());
  session.redo();
  session.redo();
  EXPECT_TRUE(session.unsaved());
  session.markSaved(session.committedEdits());
  EXPECT_FALSE(session.unsaved());
}

TEST(SceneSessionHistory, MovingTheViewAloneIsNoUnsavedEdit) {
  SceneSession session(loadScene(), RenderSettings{});
  std::string problem;
  session.navigate([](OrbitCamera& o) { o.orbit(0.4, 0.2); });
  session.navigate([](OrbitCamera& o) { o.dolly(2.0); });
  session.commit(problem);
  EXPECT_FALSE(session.unsaved()) << "orbit and dolly only look at the scene";
  EXPECT_TRUE(session.differsFromFile()) << "the title's * still says the file's camera is not the one on screen";
  session.edits().camera.nearDistance *= 2.0;  // the lens is the scene's: an edit
  session.commit(problem);
  EXPECT_TRUE(session.unsaved());
  const Camera moved = session.committedEdits().camera;
  session.markSaved(session.committedEdits());
  EXPECT_FALSE(session.unsaved());
  EXPECT_EQ(session.editedScene().parameters().camera, moved) << "what a save writes keeps the camera as it is";
}

// Pixels of tests/viewer/viewer_scene.xml's 480x300 image (see docs/viewer.md for the picture).
TEST(Pick, NamesTheMeshAndMaterialThePixelShows) {
  SceneSession session(loadScene(), RenderSettings{});
  const auto box = session.pick(160, 130);
  ASSERT_TRUE(box);
  EXPECT_EQ(describePick(*box, session.loaded(), session.edits()).rfind("picked mesh=box material=red triangle=", 0), 0u);
  EXPECT_GE(box->triangle, 2u);  // the floor's two come first
  EXPECT_LT(box->triangle, 12u);
  EXPECT_TRUE(session.takeMaterialReveal());
  EXPECT_FALSE(session.takeMaterialReveal());
  EXPECT_EQ(session.loaded().meshes[session.pick(300, 150)->mesh].id, "wedge");
  EXPECT_EQ(session.loaded().meshes[session.pick(240, 20)->mesh].id, "panel");
  const auto floor = session.pick(240, 280);
  ASSERT_TRUE(floor);
  EXPECT_EQ(session.edits().materials[floor->material].id, "floor");
  EXPECT_NEAR(floor->point.y, 0.0, 1e-9);  // the hit point lies on the floor
  EXPECT_FALSE(session.pick(5, 5));        // the background
  EXPECT_FALSE(session.selection());
  EXPECT_FALSE(session.pick(480, 0));      // outside the image
}

TEST(Pick, FramingFollowsTheSelection) {
  SceneSession session(loadScene(), RenderSettings{});
  const Bounds all = session.framingBounds();
  // The 10-wide floor is not 4x the 5-wide rest: not a ground plane, so F frames everything.
  EXPECT_DOUBLE_EQ(all.max.x - all.min.x, 10.0);
  session.pick(160, 130);
  const Bounds box = session.framingBounds();
  EXPECT_DOUBLE_EQ(box.min.x, -1.8);
  EXPECT_DOUBLE_EQ(box.max.y, 1.2);
}

TEST(AutomationScript, UndoRedoAndPick) {
  const Script s = parseScript("undo\nredo\npick 160 130\n", "t.rvs");
  ASSERT_EQ(s.commands.size(), 3u);
  EXPECT_EQ(s.commands[2].numbers, (std::vector<double>{160.0, 130.0}));
  EXPECT_THROW(parseScript("undo 2\n", "t.rvs"), ScriptError);
  EXPECT_THROW(parseScript("pick 1\n", "t.rvs"), ScriptError);
  EXPECT_THROW(parseScript("pick -1 2\n", "t.rvs"), ScriptError);
}

}  // namespace
}  // namespace rayview
