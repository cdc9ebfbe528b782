// Files the user names that are not scene files, or not files at all: each is refused at once,
// without blocking and without reading past the limit, with a message that names the file and says what
// it is.

#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <atomic>
#include <cstring>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "rayview/scene_loader.h"
#include "support/image_compare.h"

namespace rayview {
namespace {

namespace fs = std::filesystem;

// A fresh directory per test, removed afterwards.
class UserFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::testOutputDirectory() / "user_files" /
           ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(const std::string& name, const std::string& bytes) {
    const fs::path p = dir_ / name;
    std::ofstream(p, std::ios::binary) << bytes;
    return p;
  }

  // The message of the SceneError that loading `path` throws; a test failure when it loads.
  static std::string errorOf(const fs::path& path) {
    try {
      loadSceneFile(path);
    } catch (const SceneError& e) {
      EXPECT_EQ(e.diagnostic().where.file, path.string());
      return e.what();
    }
    ADD_FAILURE() << path << " loaded";
    return "";
  }

  static void expectError(const fs::path& path, int line, const std::string& part) {
    const std::string message = errorOf(path);
    std::string prefix = path.string();  // built with append: GCC 12's -Wrestrict false positive on operator+
    if (line > 0) prefix.append(":").append(std::to_string(line));
    prefix.append(": error: ");
    EXPECT_EQ(message.rfind(prefix, 0), 0u) << message;
    EXPECT_NE(message.find(part), std::string::npos) << message;
  }

  fs::path dir_;
};

const std::string kScene =
    "<scene>\n<camera><position>0 0 0</position><gaze>0 0 -1</gaze><up>0 1 0</up>"
    "<nearplane>-1 1 -1 1</nearplane><neardistance>1</neardistance><imageresolution>4 4</imageresolution>"
    "</camera>\n<textureimage>TEXTURE</textureimage>\n</scene>\n";

// ---------------------------------------------------------------- not regular files

TEST_F(UserFiles, FifoIsRefusedWithoutBlocking) {
  const fs::path fifo = dir_ / "scene.xml";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // Without the fix open() blocks until a writer comes: this one comes after 20 s, so the old code fails
  // (it then reads an empty file) instead of hanging the test run.
  std::atomic<bool> done{false};
  std::thread writer([&] {
    for (int i = 0; i < 200 && !done; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    if (!done) {
      const int fd = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
      if (fd >= 0) ::close(fd);
    }
  });
  expectError(fifo, 0, "is a named pipe (FIFO), not a regular file");
  done = true;
  writer.join();
}

TEST_F(UserFiles, DirectoryAndDevicesAreRefused) {
  expectError(dir_, 0, "is a directory");
  // /dev/zero was once read for 37 s, 2.1 GB, before "too large".
  expectError("/dev/zero", 0, "is a character device, not a regular file");
  expectError("/dev/null", 0, "is a character device, not a regular file");
}

TEST_F(UserFiles, SocketIsRefused) {
  const fs::path socketPath = dir_ / "s.xml";
  const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
  ASSERT_GE(fd, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  ASSERT_LT(socketPath.string().size(), sizeof address.sun_path);
  std::strcpy(address.sun_path, socketPath.c_str());
  ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
  expectError(socketPath, 0, "is a socket, not a regular file");
  ::close(fd);
}

// ---------------------------------------------------------------- sizes: checked before reading

TEST_F(UserFiles, TooLargeFileIsRefusedFromItsSize) {
  const fs::path big = dir_ / "big.xml";
  { std::ofstream(big) << ""; }
  fs::resize_file(big, (1ULL << 31) + 7);  // sparse: no disk space
  expectError(big, 0, "is too large (2.0 GiB; the limit is 2.0 GiB)");
}

TEST_F(UserFiles, LargeFileOfNulBytesIsNamedBinaryFromItsStart) {
  // Once read whole (82 s, 6.3 GB for 2 GiB) and then called "empty". Sparse, so only the first
  // bytes are ever read.
  const fs::path zeros = dir_ / "zeros.xml";
  { std::ofstream(zeros) << ""; }
  fs::resize_file(zeros, 1ULL << 30);
  expectError(zeros, 1, "contains NUL bytes: a binary file, not a scene file");
}

// ---------------------------------------------------------------- what the file is

TEST_F(UserFiles, BinaryAndWronglyEncodedFilesAreNamedForWhatTheyAre) {
  expectError(write("image.xml", std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16)), 0,
              "the file is a PNG image, not a scene file");
  expectError(write("photo.xml", "\xFF\xD8\xFF\xE0 JFIF"), 0, "is a JPEG image, not a scene file");
  std::string utf16 = "\xFF\xFE";
  for (char c : std::string("<scene>\n</scene>\n")) {
    utf16.push_back(c);
    utf16.push_back('\0');
  }
  expectError(write("utf16.xml", utf16), 0, "is UTF-16 text; save it as UTF-8");
  expectError(write("utf16-nobom.xml", utf16.substr(2)), 0, "is UTF-16 text; save it as UTF-8");
}

TEST_F(UserFiles, NulBytesAreReportedAtTheirLine) {
  std::string text = kScene;
  text[text.find("<textureimage>") - 1] = '\0';  // the newline ending line 2: the NUL is on line 2
  expectError(write("nul.xml", text), 2, "contains NUL bytes: a binary file, not a scene file");
}

TEST_F(UserFiles, TextThatIsNotXmlIsSaidSo) {
  expectError(write("notes.xml", "\n\nthis is a shopping list\nmilk\n"), 3,
              "the file is not XML: no element found (it starts with 'this is a shopping list')");
  expectError(write("empty.xml", " \n\n"), 0, "no <scene> element: the file is empty");
}

// ---------------------------------------------------------------- texture images

::testing::AssertionResult hasWarning(const LoadedScene& loaded, const std::string& part) {
  std::string all;
  for (const Diagnostic& d : loaded.warnings) {
    if (d.message.find("texture image") != std::string::npos && d.message.find(part) != std::string::npos)
      return ::testing::AssertionSuccess();
    all += "\n  " + d.format();
  }
  return ::testing::AssertionFailure() << "no texture warning with '" << part << "'; have:" << all;
}

TEST_F(UserFiles, TextureThatIsAFifoOrTooLargeIsAWarningNotAHang) {
  const fs::path fifo = dir_ / "fifo.png";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::atomic<bool> done{false};
  std::thread writer([&] {  // as above: unblocks the old code after 20 s so that it fails, not hangs
    for (int i = 0; i < 200 && !done; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    if (!done) {
      const int fd = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
      if (fd >= 0) ::close(fd);
    }
  });
  std::string text = kScene;
  text.replace(text.find("TEXTURE"), 7, fifo.string());
  const LoadedScene withFifo = loadSceneFile(write("fifo.xml", text));
  done = true;
  writer.join();
  EXPECT_TRUE(hasWarning(withFifo, "is a named pipe (FIFO), not a regular file"));
  EXPECT_FALSE(withFifo.scene.texture.has_value());

  const fs::path big = dir_ / "big.png";
  { std::ofstream(big) << ""; }
  fs::resize_file(big, (1ULL << 30) + 1);
  text = kScene;
  text.replace(text.find("TEXTURE"), 7, big.string());
  const LoadedScene withBig = loadSceneFile(write("big.xml", text));
  EXPECT_TRUE(hasWarning(withBig, "is too large (1.0 GiB; the limit is 1.0 GiB); tried"));
}

}  // namespace
}  // namespace rayview
