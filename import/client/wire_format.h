#pragma once
// What the import worker writes on its standard output and the client reads: a magic, a kind (a scene, or an
// error message), length-prefixed blobs, and an end mark. Native byte order: both ends are the same build.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "rayview/input_files.h"
#include "rayview/scene.h"

namespace rayview::wire {

inline constexpr char kMagic[8] = {'R', 'V', 'I', 'M', 'P', 'O', 'R', 'T'};
inline constexpr char kEnd[8] = {'R', 'V', 'I', 'M', 'P', 'E', 'N', 'D'};
// The line an Error carries when it is a failed write (ModelWriteError), not a bad input.
inline constexpr char kWriteFailureLine[] = "write";
enum class Kind : std::uint32_t { Scene = 1, Error = 2, Done = 3 };

// The parts of an imported scene, in the order they are sent.
struct SceneMessage {
  SceneParameters parameters;  // camera, lights, materials, in the scene codec (checked by parametersProblem)
  std::string summary;
  std::vector<std::string> warnings;
  SceneGeometry geometry;     // textureImage names the texture; texture holds it decoded
  // Every file reading the model read (MTL files, textures, buffers) as role and path: rayview never writes on one.
  std::vector<RememberedInput> filesRead;
};

// Each returns false when the stream cannot be written (a closed pipe).
bool writeScene(std::FILE* out, const SceneMessage& message);
bool writeError(std::FILE* out, const std::string& message);
bool writeDone(std::FILE* out, const std::string& summary);

// Reads one message from `fd` to its end. Returns "" and fills exactly one of `scene` / `error` (a Done's summary
// goes to scene.summary); otherwise what is wrong with the stream ("truncated", "not an import answer", ...).
// `error` is set for Kind::Error. Every length is checked against what a scene can hold before it is allocated.
std::string readMessage(int fd, Kind& kind, SceneMessage& scene, std::string& error);

}  // namespace rayview::wire
