// rayview-import: the worker that reads a model (or writes one) for rayview, in a process of its own, and
// answers on its standard output in the form of wire_format.h. Not a user command: rayview starts it.
//
//   rayview-import read MODEL [--up y|z] [--resolution WxH]
//   rayview-import export SCENE.xml OUTPUT

#include <unistd.h>

#include <cstdio>
#include <new>
#include <string>

#include "rayview/diagnostics.h"
#include "rayview/model_import.h"
#include "rayview/scene_loader.h"
#include "rayview/scene_writer.h"
#include "wire_format.h"

namespace rayview {
namespace {

int usage() {
  wire::writeError(stdout, "0\nusage: rayview-import read MODEL [--up y|z] [--resolution WxH] | export SCENE OUTPUT");
  return 2;
}

int readCommand(int argc, char** argv) {
  ModelImportOptions options;
  for (int i = 3; i + 1 < argc; i += 2) {
    const std::string name = argv[i], value = argv[i + 1];
    if (name == "--up" && parseModelUpAxis(value, options.up)) continue;
    if (name == "--resolution" && parseResolution(value, options.width, options.height)) continue;
    return usage();
  }
  ModelScene model = readModel(argv[2], options);
  wire::SceneMessage message;
  message.parametersXml = sceneToXml(model.scene.parameters(), SceneGeometry{}, model.scene.textureImage,
                                     NumberText::FloatWhenExact);
  message.summary = std::move(model.summary);
  message.warnings = std::move(model.warnings);
  message.geometry = std::move(static_cast<SceneGeometry&>(model.scene));
  return wire::writeScene(stdout, message) ? 0 : 1;
}

int exportCommand(char** argv) {
  LoadedScene loaded = loadSceneFile(argv[2]);
  exportScene(loaded.scene, argv[3]);
  return wire::writeDone(stdout, "") ? 0 : 1;
}

int run(int argc, char** argv) {
  const std::string command = argc > 2 ? argv[1] : "";
  try {
    if (command == "read" && argc % 2 == 1) return readCommand(argc, argv);
    if (command == "export" && argc == 4) return exportCommand(argv);
    return usage();
  } catch (const SceneError& error) {
    // The line travels with the message, so the client's error is located as the loader's would be.
    wire::writeError(stdout, std::to_string(error.diagnostic().where.line) + "\n" + error.diagnostic().message);
  } catch (const std::bad_alloc&) {
    wire::writeError(stdout, "0\nout of memory reading the model");
  } catch (const std::exception& error) {
    wire::writeError(stdout, std::string("0\ncannot be read as a model: ") + error.what());
  }
  return 2;
}

}  // namespace
}  // namespace rayview

int main(int argc, char** argv) {
  const int status = rayview::run(argc, argv);
  std::fflush(stdout);
  // No destructors at exit: the answer is out, and nothing a broken file left behind can fail the exit now.
  ::_exit(status == 2 ? 0 : status);
}
