// rayview-import: the worker that reads a model (or writes one) for rayview, in a process of its own, and
// answers on its standard output in the form of wire_format.h. Not a user command: rayview starts it.
//
//   rayview-import read MODEL [--up y|z] [--resolution WxH] [--camera shown|file|auto] [--lights shown|file|kit]
//   rayview-import export SCENE.wire OUTPUT     (the scene as rayview's client wrote it: wire_format.h)

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <new>
#include <string>

#include "rayview/diagnostics.h"
#include "rayview/input_files.h"
#include "rayview/model_client.h"
#include "rayview/model_import.h"
#include "wire_format.h"

namespace rayview {
namespace {

using wire::kWriteFailureLine;

// Bounds on what reading one file may take: Assimp's glTF reader was seen to take 12.9 GB and 40 s for a 284-byte
// file (fuzz_import). Past the memory bound an allocation fails (a clean "out of memory" answer); past the CPU
// bound the kernel ends the worker, which rayview reports as a crash of the importer.
void limitResources(const char* file) {
  struct stat info {};
  const double bytes = ::stat(file, &info) == 0 ? static_cast<double>(info.st_size) : 0.0;
#ifndef RAYVIEW_SANITIZED  // a sanitizer's shadow memory needs terabytes of address space (see below instead)
  const double memory = 2.0 * (1 << 30) + 32.0 * bytes;  // the 10M-triangle PLY peaks at 2.3 times its size
  const rlimit as{static_cast<rlim_t>(memory), static_cast<rlim_t>(memory)};
  ::setrlimit(RLIMIT_AS, &as);
#endif
  rlim_t seconds = static_cast<rlim_t>(20.0 + bytes / (1 << 20));  // 1M triangles (18 MiB) take 0.1 s
  if (const char* given = std::getenv("RAYVIEW_IMPORT_CPU_SECONDS"); given && std::atoi(given) > 0)
    seconds = static_cast<rlim_t>(std::atoi(given));  // the fuzz target's shorter bound
  const rlimit cpu{seconds, seconds + 5};  // SIGXCPU at the bound, SIGKILL should that be caught
  ::setrlimit(RLIMIT_CPU, &cpu);
  // A worker blocked without using CPU (a read that never returns) is never stopped by the CPU bound: SIGALRM's
  // default action ends it once three times that bound has passed on the clock, however loaded the machine.
  unsigned wall = static_cast<unsigned>(3 * seconds);
  if (const char* given = std::getenv("RAYVIEW_IMPORT_WALL_SECONDS"); given && std::atoi(given) > 0)
    wall = static_cast<unsigned>(std::atoi(given));
  ::alarm(wall);
}

int usage() {
  wire::writeError(stdout, "0\nusage: rayview-import read MODEL [--up y|z] [--resolution WxH] [--camera shown|file|auto] "
                               "[--lights shown|file|kit] | export SCENE.wire OUTPUT");
  return 2;
}

int readCommand(int argc, char** argv) {
  ModelImportOptions options;
  for (int i = 3; i + 1 < argc; i += 2) {
    const std::string name = argv[i], value = argv[i + 1];
    if (name == "--up" && parseModelUpAxis(value, options.up)) continue;
    if (name == "--resolution" && parseResolution(value, options.width, options.height)) continue;
    if (name == "--camera" && parseModelCamera(value, options.camera)) continue;
    if (name == "--lights" && parseModelLights(value, options.lights)) continue;
    return usage();
  }
  ModelScene model = readModel(argv[2], options);
  wire::SceneMessage message;
  message.parameters = std::move(model.scene.parameters());
  message.summary = std::move(model.summary);
  message.warnings = std::move(model.warnings);
  message.geometry = std::move(static_cast<SceneGeometry&>(model.scene));
  message.filesRead = rememberedInputs();
  return wire::writeScene(stdout, message) ? 0 : 1;
}

// The scene rayview opened, as its client handed it over in the scene codec (checked again here).
int exportCommand(char** argv) {
  const int fd = ::open(argv[2], O_RDONLY | O_CLOEXEC);
  wire::Kind kind = wire::Kind::Error;
  wire::SceneMessage message;
  std::string error;
  const std::string problem = fd < 0 ? "cannot be opened" : wire::readMessage(fd, kind, message, error);
  if (fd >= 0) ::close(fd);
  if (!problem.empty() || kind != wire::Kind::Scene)
    throwSceneError({argv[2], 0}, "the scene handed to the exporter is unusable (" + problem + ")");
  Scene scene;
  scene.parameters() = std::move(message.parameters);
  static_cast<SceneGeometry&>(scene) = std::move(message.geometry);
  if (std::string bad = parametersProblem(scene); !bad.empty() || !(bad = wholenessProblem(scene)).empty())
    throwSceneError({argv[2], 0}, "the scene handed to the exporter is unusable (" + bad + ")");
  exportScene(scene, argv[3]);
  return wire::writeDone(stdout, "") ? 0 : 1;
}

int run(int argc, char** argv) {
  const std::string command = argc > 2 ? argv[1] : "";
  try {
    if (argc > 2 && std::getenv("RAYVIEW_IMPORT_NO_LIMITS") == nullptr) limitResources(argv[2]);
    if (command == "read" && argc % 2 == 1) return readCommand(argc, argv);
    if (command == "export" && argc == 4) return exportCommand(argv);
    return usage();
  } catch (const SceneError& error) {
    // The line travels with the message, so the client's error is located as the loader's would be. One in a file
    // the model names (its MTL) names that file and line in the message: the client names the model.
    const SourceLocation& where = error.diagnostic().where;
    if (argc > 2 && !where.file.empty() && where.file != argv[2])
      wire::writeError(stdout, "0\nin " + where.file + ", line " + std::to_string(where.line) + ": " +
                                   error.diagnostic().message);
    else
      wire::writeError(stdout, std::to_string(where.line) + "\n" + error.diagnostic().message);
  } catch (const ModelWriteError& error) {
    wire::writeError(stdout, std::string(kWriteFailureLine) + "\n" + error.what());
  } catch (const std::bad_alloc&) {
    wire::writeError(stdout, "0\nout of memory reading the model");
  } catch (const std::exception& error) {
    wire::writeError(stdout, std::string("0\ncannot be read as a model: ") + error.what());
  }
  return 2;
}

}  // namespace
}  // namespace rayview

#ifdef RAYVIEW_SANITIZED
// The memory bound of sanitizer builds: an allocation over 4 GiB ends the worker, which rayview reports.
extern "C" const char* __asan_default_options() { return "max_allocation_size_mb=4096:allocator_may_return_null=1"; }
#endif

int main(int argc, char** argv) {
  const int status = rayview::run(argc, argv);
  std::fflush(stdout);
  // No destructors at exit: the answer is out, and nothing a broken file left behind can fail the exit now.
  ::_exit(status == 2 ? 0 : status);
}
