// The file system Assimp reads a model's other files through (MTL files, glTF buffers): it refuses anything that
// is not a regular file, since opening a FIFO, socket or device would block the importer for ever, and it keeps
// the names of the files it opened so that the worker can report every file the model made it read.
#pragma once

#include <assimp/DefaultIOSystem.h>

#include <string>
#include <vector>

namespace rayview::model {

class GuardedIOSystem : public Assimp::DefaultIOSystem {
 public:
  // Assimp's own Exists opens the file to see it is there, which blocks on a FIFO as Open would.
  bool Exists(const char* file) const override;
  Assimp::IOStream* Open(const char* file, const char* mode = "rb") override;
  // The first file refused ("" when none): the reader fails naming it rather than with Assimp's own sentence.
  const std::string& refused() const { return refused_; }
  const std::vector<std::string>& opened() const { return opened_; }

 private:
  std::string refused_;
  std::vector<std::string> opened_;
};

}  // namespace rayview::model
