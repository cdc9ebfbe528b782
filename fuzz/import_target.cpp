// Fuzz target "import": opening a model on any bytes. Byte 0 picks how:
//  - bit 7 clear: rayview's own readers in this process, where coverage guides the fuzzer: with bit 6, an OBJ and
//    its MTL (the bytes before a line "#mtl" are the OBJ, those after it the MTL, which the OBJ names first: the MTL's
//    numbers and texture paths), else bit 0: .stl, or .ply;
//  - bit 7 set: as rayview opens any model (rayview/model_client.h), through the worker (libexec/rayview-import),
//    with the extension kExtensions[(byte & 0x7f) % N]. Assimp does crash on some inputs; the property is that
//    rayview does not: every outcome is a scene or a SceneError.
// Either a SceneError, or the scene is whole (wholenessProblem) with finite vertices and a usable camera.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <unistd.h>

#include "fuzz_input.h"
#include "rayview/diagnostics.h"
#include "rayview/model_client.h"
#include "rayview/model_import.h"

namespace {

constexpr const char* kExtensions[] = {".ply", ".stl", ".obj", ".gltf", ".glb", ".off", ".dae", ".3ds", ".fbx", ".x"};

void check(const rayview::Scene& scene) {
  if (!rayview::wholenessProblem(scene).empty()) rayview::fuzz::fail("an imported scene that is not whole");
  for (const auto& v : scene.vertices)
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) rayview::fuzz::fail("a vertex not finite");
  const rayview::Camera& c = scene.camera;
  if (!std::isfinite(c.position.x + c.position.y + c.position.z) || !(c.right > c.left) || !(c.top > c.bottom))
    rayview::fuzz::fail("an unusable camera");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fs = std::filesystem;
  if (size < 1) return 0;
  const bool viaWorker = (data[0] & 0x80) != 0;
  const bool withMtl = !viaWorker && (data[0] & 0x40) != 0;
  const char* extension = viaWorker ? kExtensions[(data[0] & 0x7f) % std::size(kExtensions)]
                          : withMtl ? ".obj"
                                    : ((data[0] & 1) ? ".stl" : ".ply");
  const fs::path scratch =
      fs::temp_directory_path() / ("rayview-fuzz-import-" + std::to_string(::getpid()) + extension);
  const fs::path library = fs::path(scratch).replace_extension(".mtl");
  const std::string bytes(reinterpret_cast<const char*>(data + 1), size - 1);
  const auto write = [](const fs::path& file, const std::string& text) {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    if (!out) rayview::fuzz::fail("cannot write the scratch file");
  };
  if (withMtl) {
    const std::size_t split = bytes.find("\n#mtl\n");
    write(library, split == std::string::npos ? std::string() : bytes.substr(split + 6));
    write(scratch, "mtllib " + library.filename().string() + "\n" + bytes.substr(0, split));
  } else {
    write(scratch, bytes);
  }
  // The worker's CPU bound, short: Assimp spins on some inputs until the bound ends it (a clean error).
  static const bool bounded = ::setenv("RAYVIEW_IMPORT_CPU_SECONDS", "3", 1) == 0;
  (void)bounded;
  rayview::ModelImportOptions options;
  options.width = 64;
  options.height = 48;
  try {
    if (viaWorker) check(rayview::importModel(scratch, options).loaded.scene);
    else check(rayview::readModel(scratch, options).scene);
  } catch (const rayview::SceneError&) {
  }
  std::error_code ec;
  fs::remove(scratch, ec);
  if (withMtl) fs::remove(library, ec);
  return 0;
}
