#include "rayview/model_client.h"

#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "rayview/diagnostics.h"
#include "rayview/input_files.h"
#include "wire_format.h"

extern char** environ;

namespace rayview {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const fs::path& file, const std::string& message) {
  throwSceneError(SourceLocation{file.string(), 0}, message);
}

struct WorkerAnswer {
  wire::Kind kind = wire::Kind::Error;
  wire::SceneMessage scene;
  std::string error;
};

std::string describeStatus(int status) {
  if (WIFSIGNALED(status) && (WTERMSIG(status) == SIGXCPU || WTERMSIG(status) == SIGKILL ||
                            WTERMSIG(status) == SIGALRM))
    return "the importer was stopped on this file (it ran past its time or memory bound, or waited past its "
           "clock bound)";
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    const char* name = sigdescr_np(signal);
    return "the importer crashed on this file (signal " + std::to_string(signal) + ", " + (name ? name : "?") + ")";
  }
  return "the importer failed on this file (exit status " + std::to_string(WEXITSTATUS(status)) + ")";
}

// Runs the worker with `arguments`, reads its one answer from a pipe and waits for it. Any way the child can go
// wrong (not found, killed by a signal, a bad exit, a broken answer) becomes a SceneError about `file`.
WorkerAnswer runWorker(const fs::path& file, const std::vector<std::string>& arguments) {
  const fs::path worker = importWorkerPath();
  int pipeFds[2];
  if (::pipe2(pipeFds, O_CLOEXEC) != 0) fail(file, std::string("cannot start the importer: ") + std::strerror(errno));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipeFds[1], STDOUT_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  // Assimp's own chatter on a bad file would only repeat the one message the answer carries.
  if (!std::getenv("RAYVIEW_IMPORT_DEBUG"))
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  std::vector<std::string> all{worker.string()};
  all.insert(all.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t child = 0;
  const int spawned = ::posix_spawn(&child, worker.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(pipeFds[1]);
  if (spawned != 0) {
    ::close(pipeFds[0]);
    fail(file, "cannot start the importer " + worker.string() + ": " + std::strerror(spawned));
  }
  WorkerAnswer answer;
  const std::string problem = wire::readMessage(pipeFds[0], answer.kind, answer.scene, answer.error);
  ::close(pipeFds[0]);  // a worker still writing gets SIGPIPE rather than blocking us
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFSIGNALED(status) || (problem.empty() && answer.kind != wire::Kind::Error && WEXITSTATUS(status) != 0) ||
      (!problem.empty() && WIFEXITED(status) && WEXITSTATUS(status) != 0))
    fail(file, describeStatus(status));
  if (!problem.empty()) fail(file, "the importer's answer is unusable (" + problem + ")");
  if (answer.kind == wire::Kind::Error) {
    // "LINE\nmessage": the line of a scene file's error (0 for a model's).
    const std::size_t newline = answer.error.find('\n');
    if (answer.error.compare(0, newline, wire::kWriteFailureLine) == 0 && newline != std::string::npos)
      throw ModelWriteError(answer.error.substr(newline + 1));
    int line = 0;
    if (newline != std::string::npos) line = std::atoi(answer.error.substr(0, newline).c_str());
    throwSceneError(SourceLocation{file.string(), std::max(line, 0)},
                    newline == std::string::npos ? answer.error : answer.error.substr(newline + 1));
  }
  return answer;
}

std::vector<std::string> readArguments(const fs::path& path, const ModelImportOptions& options) {
  return {"read", path.string(), "--up", options.up == ModelUpAxis::Z ? "z" : "y", "--resolution",
          std::to_string(options.width) + "x" + std::to_string(options.height),
          "--camera", modelCameraWord(options.camera), "--lights", modelLightsWord(options.lights)};
}

// The worker's answer as the loader's result: its parameters and geometry moved in and checked as the loader checks
// every value it reads (parametersProblem, wholenessProblem).
LoadedScene toLoadedScene(const fs::path& path, wire::SceneMessage&& message) {
  LoadedScene loaded;
  loaded.scene.parameters() = std::move(message.parameters);
  if (const std::string problem = parametersProblem(loaded.scene); !problem.empty())
    fail(path, "has values rayview cannot use (" + problem +
                   "; a value that is not finite or too large, in the model or in what is made up from it)");
  static_cast<SceneGeometry&>(loaded.scene) = std::move(message.geometry);
  loaded.scene.sourcePath = path;
  for (const glm::dvec3& v : loaded.scene.vertices)
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
      fail(path, "the importer's answer is unusable (a vertex is not finite)");
  if (const std::string problem = wholenessProblem(loaded.scene); !problem.empty())
    fail(path, "the importer's answer is unusable (" + problem + ")");
  loaded.warnings.clear();
  for (std::string& text : message.warnings) {
    Diagnostic warning;
    warning.where.file = path.string();
    warning.message = std::move(text);
    loaded.warnings.push_back(std::move(warning));
  }
  return loaded;
}

}  // namespace

fs::path importWorkerPath() {
  if (const char* overridden = std::getenv("RAYVIEW_IMPORT_WORKER"); overridden && *overridden) return overridden;
  char self[PATH_MAX];
  const ssize_t length = ::readlink("/proc/self/exe", self, sizeof self - 1);
  if (length > 0) {
    self[length] = '\0';
    const fs::path beside = fs::path(self).parent_path() / "libexec" / "rayview-import";
    std::error_code ec;
    if (fs::exists(beside, ec)) return beside;
  }
#ifdef RAYVIEW_IMPORT_WORKER_BUILD_PATH
  return RAYVIEW_IMPORT_WORKER_BUILD_PATH;
#else
  return "rayview-import";
#endif
}

ImportedModel importModel(const fs::path& path, const ModelImportOptions& options) {
  WorkerAnswer answer = runWorker(path, readArguments(path, options));
  if (answer.kind != wire::Kind::Scene) fail(path, "the importer's answer is unusable (not a scene)");
  ImportedModel model;
  model.summary = answer.scene.summary;
  // What the worker read is this process's input as much as the model is: no output may land on it.
  for (const RememberedInput& file : answer.scene.filesRead) rememberInput(file.path, file.role);
  model.loaded = toLoadedScene(path, std::move(answer.scene));
  return model;
}

LoadedScene loadModelScene(const fs::path& path, const ModelImportOptions& options) {
  return importModel(path, options).loaded;
}

namespace {

// A file in the temporary directory that holds the scene for the worker, removed however the export ends.
class SceneHandoff {
 public:
  explicit SceneHandoff(const fs::path& about) : about_(about) {
    const char* dir = std::getenv("TMPDIR");
    path_ = (dir && *dir ? std::string(dir) : std::string("/tmp")) + "/rayview-export-XXXXXX";
    const int fd = ::mkstemp(path_.data());
    if (fd < 0) fail(about_, std::string("cannot hand the scene to the exporter: ") + std::strerror(errno));
    file_ = ::fdopen(fd, "wb");
    if (!file_) {
      ::close(fd);
      fail(about_, std::string("cannot hand the scene to the exporter: ") + std::strerror(errno));
    }
  }
  ~SceneHandoff() {
    if (file_) std::fclose(file_);
    ::unlink(path_.c_str());
  }
  SceneHandoff(const SceneHandoff&) = delete;
  SceneHandoff& operator=(const SceneHandoff&) = delete;

  void write(const Scene& scene) {
    wire::SceneMessage message;
    message.parameters = scene.parameters();
    message.geometry = scene.geometry();
    const bool written = wire::writeScene(file_, message);
    const bool closed = std::fclose(file_) == 0;
    file_ = nullptr;
    if (!written || !closed) fail(about_, "cannot hand the scene to the exporter (is the temporary directory full?)");
  }
  const std::string& path() const { return path_; }

 private:
  fs::path about_;
  std::string path_;
  std::FILE* file_ = nullptr;
};

}  // namespace

void exportOpenedScene(const Scene& scene, const fs::path& outputPath) {
  const fs::path about = scene.sourcePath.empty() ? fs::path("default scene") : scene.sourcePath;
  SceneHandoff handoff(about);
  handoff.write(scene);
  WorkerAnswer answer = runWorker(about, {"export", handoff.path(), outputPath.string()});
  if (answer.kind != wire::Kind::Done) fail(about, "the exporter's answer is unusable (not done)");
}

}  // namespace rayview
