// Fuzz target "import": reading a model (rayview_import: rayview's own PLY and STL readers, Assimp for the rest)
// on any bytes. Byte 0 picks the file's extension (and so the reader), the rest is the file. It runs the worker's
// reading in this process, so a crash in it is found here even though rayview itself would survive it. Either
// readModel throws SceneError, or the scene is whole (wholenessProblem) with finite vertices and a usable camera.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include "fuzz_input.h"
#include "rayview/diagnostics.h"
#include "rayview/model_import.h"

namespace {

constexpr const char* kExtensions[] = {".ply", ".stl", ".obj", ".gltf", ".glb", ".off", ".dae", ".3ds", ".fbx", ".x"};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fs = std::filesystem;
  if (size < 1) return 0;
  const char* extension = kExtensions[data[0] % std::size(kExtensions)];
  const fs::path scratch =
      fs::temp_directory_path() / ("rayview-fuzz-import-" + std::to_string(::getpid()) + extension);
  {
    std::ofstream out(scratch, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
    if (!out) rayview::fuzz::fail("cannot write the scratch file");
  }
  try {
    rayview::ModelImportOptions options;
    options.width = 64;
    options.height = 48;
    const rayview::ModelScene model = rayview::readModel(scratch, options);
    if (!rayview::wholenessProblem(model.scene).empty()) rayview::fuzz::fail("an imported scene that is not whole");
    for (const auto& v : model.scene.vertices)
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) rayview::fuzz::fail("a vertex not finite");
    if (!std::isfinite(model.scene.camera.position.x) || !(model.scene.camera.right > model.scene.camera.left))
      rayview::fuzz::fail("an unusable camera");
  } catch (const rayview::SceneError&) {
  }
  std::error_code ec;
  fs::remove(scratch, ec);
  return 0;
}
