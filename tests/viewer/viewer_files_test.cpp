// The viewer's files: its recent-files list read through the bounded reader (a FIFO or /dev/zero in its place
// is an empty list at once) and written through a symlink; its saves refusing the open scene's inputs; scripts
// failing when a screenshot or view save fails, and refusing times that would overflow the clock.
#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "automation_script.h"
#include "numbered_file.h"
#include "rayview/input_files.h"
#include "rayview/scene_loader.h"
#include "recent_files.h"
#include "script_runner.h"
#include "viewer_fixtures.h"

namespace rayview {
namespace {

using namespace viewer_testing;

TEST(RecentFilesList, AFifoOrADeviceInItsPlaceIsAnEmptyListAtOnce) {
  const fs::path directory = freshDirectory("recent_fifo");
  const fs::path fifo = directory / "recent.txt";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_TRUE(RecentFiles(fifo).paths().empty());  // once blocked here forever, waiting for a writer
  EXPECT_TRUE(RecentFiles("/dev/zero").paths().empty());  // once read until memory ran out
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20));  // a hang, not a timing figure
}

TEST(RecentFilesList, ASymlinkedListIsWrittenThroughItsLink) {
  const fs::path directory = freshDirectory("recent_link");
  fs::create_directories(directory / "dotfiles");
  writeText(directory / "dotfiles" / "recent.txt", "/old.xml\n");
  const fs::path link = directory / "recent.txt";
  fs::create_symlink("dotfiles/recent.txt", link);
  RecentFiles recent(link);
  ASSERT_EQ(recent.paths().size(), 1u);
  EXPECT_TRUE(recent.add("/new.xml"));
  EXPECT_TRUE(fs::is_symlink(link));
  std::ifstream in(directory / "dotfiles" / "recent.txt");
  std::string first;
  std::getline(in, first);
  EXPECT_EQ(first, "/new.xml");
}

TEST(ViewerSaves, NeverReplaceTheOpenScenesFilesLoadedOrNot) {
  const fs::path directory = freshDirectory("saves");
  std::string xml;
  {
    std::ifstream in(kViewerScene);
    xml.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const std::size_t end = xml.rfind("</scene>");
  ASSERT_NE(end, std::string::npos);
  xml.insert(end, "<textureimage>tex.png</textureimage>\n");
  writeText(directory / "scene.xml", xml);
  writeText(directory / "tex.png", "not an image");
  forgetInputs();
  const LoadedScene loaded = loadSceneFile(directory / "scene.xml");
  const std::string scenePath = (directory / "scene.xml").string();
  for (const fs::path& output : {directory / "tex.png", directory / "." / "tex.png", directory / "scene.xml"})
    EXPECT_THROW(refusingInputs(output.string(), scenePath, &loaded.scene), ImageIoError) << output;
  EXPECT_EQ(refusingInputs((directory / "new.png").string(), scenePath, &loaded.scene), (directory / "new.png").string());
}

class FailingCaptureHost : public FakeHost {
 public:
  FailingCaptureHost() : FakeHost(nullptr) {}
  std::optional<std::string> captureOutcome() const override { return outcome; }
  std::optional<std::string> outcome;
};

TEST(ScriptCaptures, AFailedScreenshotOrViewSaveFailsTheScript) {
  for (const char* command : {"screenshot /no/such/dir/shot.png\nquit 0\n", "save-view /no/such/dir/view.png\nquit 0\n"}) {
    FailingCaptureHost host;
    ScriptRunner runner(parseScript(command, "t"));
    host.frame(runner);
    host.frame(runner);
    EXPECT_TRUE(runner.running()) << command;  // waiting for the frame to be drawn and read back
    EXPECT_EQ(host.exitCode, -1);
    host.outcome = "cannot write /no/such/dir: No such file or directory";
    host.frame(runner);
    ASSERT_TRUE(runner.failed()) << command;
    EXPECT_NE(runner.failure().find("cannot write"), std::string::npos) << runner.failure();
    EXPECT_EQ(host.exitCode, -1);  // the quit after it never ran
  }
  FailingCaptureHost host;
  host.outcome = std::string();
  ScriptRunner runner(parseScript("screenshot shot.png\nquit 0\n", "t"));
  for (int i = 0; i < 4 && runner.running(); ++i) host.frame(runner);
  EXPECT_FALSE(runner.failed());
  EXPECT_EQ(host.exitCode, 0);
}

TEST(ScriptCaptures, TimesThatWouldOverflowTheClockAreRefused) {
  for (const char* text : {"sleep 1e10\n", "wait-final 9.3e9\n", "measure-tradeoff 0.5 1e12\n", "sleep 1e300\n"})
    EXPECT_THROW(parseScript(text, "t"), ScriptError) << text;
  EXPECT_NO_THROW(parseScript("sleep 1000000\nwait-final 3600\n", "t"));
}

}  // namespace
}  // namespace rayview
