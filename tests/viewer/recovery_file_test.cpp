// The recovery file of unsaved edits (ui/recovery_file.cpp): where it goes, what it holds, when it is written and
// removed. Part of viewer_logic_test; the kill -9 and the restart are the window test `recovery`.
#include <chrono>
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include "recovery_file.h"
#include "scene_session.h"
#include "viewer_fixtures.h"

namespace rayview {
namespace {

using namespace viewer_testing;
using namespace std::chrono_literals;

// RAYVIEW_RECOVERY_DIR for one test, the variable as it was afterwards.
class RecoveryDirectory {
 public:
  explicit RecoveryDirectory(const fs::path& dir) {
    if (const char* old = std::getenv("RAYVIEW_RECOVERY_DIR")) old_ = old;
    setenv("RAYVIEW_RECOVERY_DIR", dir.c_str(), 1);
  }
  ~RecoveryDirectory() {
    if (old_) setenv("RAYVIEW_RECOVERY_DIR", old_->c_str(), 1);
    else unsetenv("RAYVIEW_RECOVERY_DIR");
  }

 private:
  std::optional<std::string> old_;
};

TEST(RecoveryFile, HoldsTheEditsAndTheScenesPathWhateverItsCharacters) {
  const fs::path dir = freshDirectory("recovery_roundtrip");
  const RecoveryDirectory env(dir);
  const std::string odd = (dir / "a--b -> 100%.xml").string();
  const fs::path file = recoveryFileFor(odd);
  EXPECT_EQ(file.parent_path(), dir);
  EXPECT_NE(recoveryFileFor(odd), recoveryFileFor((dir / "other.xml").string())) << "one file per scene";
  SceneSession session(loadParts(), RenderSettings{});
  SceneParameters edits = session.edits();
  edits.materials[1].diffuse = Color{0.125f, 0.5f, 0.75f};
  edits.camera.position.x += 0.1;
  edits.maxRayDepth = 5;
  writeRecoveryFile(file, odd, edits);
  const std::optional<RecoveredEdits> back = readRecoveryFile(file);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->scenePath, odd);
  EXPECT_EQ(back->edits, edits) << "every value reads back exactly";
  EXPECT_EQ(recoveryMismatch(back->edits, session.loaded().parameters()), "");
  EXPECT_FALSE(readRecoveryFile(dir / "none.recovery.xml").has_value());
}

TEST(RecoveryFile, EditsThatNoLongerFitTheSceneAreNotRestored) {
  SceneSession session(loadParts(), RenderSettings{});
  SceneParameters edits = session.edits();
  edits.materials.pop_back();
  EXPECT_NE(recoveryMismatch(edits, session.loaded().parameters()), "");
  edits = session.edits();
  edits.materials[0].id = "renamed";
  EXPECT_NE(recoveryMismatch(edits, session.loaded().parameters()), "");
}

TEST(RecoveryFile, AFileThatIsNotOneIsAnErrorNamingIt) {
  const fs::path dir = freshDirectory("recovery_bad");
  writeText(dir / "x.recovery.xml", "<scene></scene>\n");
  try {
    readRecoveryFile(dir / "x.recovery.xml");
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_NE(e.diagnostic().format().find("x.recovery.xml"), std::string::npos) << e.diagnostic().format();
  }
}

TEST(RecoveryKeeper, WritesWithinTheIntervalAndRemovesOnceNothingIsUnsaved) {
  const fs::path dir = freshDirectory("recovery_keeper");
  const RecoveryDirectory env(dir);
  const std::string scene = (dir / "scene.xml").string();
  const fs::path file = recoveryFileFor(scene);
  SceneSession session(loadParts(), RenderSettings{});
  RecoveryKeeper keeper;
  std::string problem;
  const auto t0 = RecoveryKeeper::Clock::now();
  session.navigate([](OrbitCamera& o) { o.orbit(0.3, 0.1); });
  session.commit(problem);
  keeper.keep(&session, scene, false, t0);
  EXPECT_FALSE(fs::exists(file)) << "moving the view alone is nothing to keep";
  session.edits().background = Color{9.0f, 8.0f, 7.0f};
  session.commit(problem);
  keeper.keep(&session, scene, true, t0);
  EXPECT_FALSE(fs::exists(file)) << "paused while an offer is up";
  keeper.keep(&session, scene, false, t0);
  ASSERT_TRUE(fs::exists(file)) << "the first edit after a while is written at once";
  session.edits().background = Color{1.0f, 2.0f, 3.0f};
  session.commit(problem);
  keeper.keep(&session, scene, false, t0 + 300ms);
  ASSERT_TRUE(keeper.secondsUntilDue(t0 + 300ms).has_value());
  EXPECT_NEAR(*keeper.secondsUntilDue(t0 + 300ms), 0.7, 1e-6) << "the next write waits for the interval";
  EXPECT_EQ(readRecoveryFile(file)->edits.background, (Color{9.0f, 8.0f, 7.0f}));
  keeper.keep(&session, scene, false, t0 + kRecoveryInterval);
  EXPECT_EQ(readRecoveryFile(file)->edits.background, (Color{1.0f, 2.0f, 3.0f}));
  EXPECT_EQ(readRecoveryFile(file)->edits.camera, session.committedEdits().camera) << "the camera is kept with them";
  session.markSaved(session.committedEdits());
  keeper.keep(&session, scene, false, t0 + 2 * kRecoveryInterval);
  EXPECT_FALSE(fs::exists(file)) << "saved: nothing to recover";
}

TEST(RecoveryKeeper, AnotherViewersFileWaitsForItsOfferAndDiscardRemovesOnlyOurs) {
  const fs::path dir = freshDirectory("recovery_others");
  const RecoveryDirectory env(dir);
  const std::string scene = (dir / "scene.xml").string();
  const fs::path file = recoveryFileFor(scene);
  SceneSession session(loadParts(), RenderSettings{});
  writeRecoveryFile(file, scene, session.edits());
  RecoveryKeeper keeper;
  keeper.keep(&session, scene, false, RecoveryKeeper::Clock::now());
  keeper.discard(scene);
  EXPECT_TRUE(fs::exists(file)) << "a file this process did not write is left for its offer";
}

}  // namespace
}  // namespace rayview
