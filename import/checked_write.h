// The file system Assimp's exporter writes through: Assimp ignores a short write and never checks that a file
// closed whole, so a full disk gave "written" and a cut-off file. Each stream here remembers the first failure
// (a short write, a failed flush or close) with its reason, which the export then reports instead of renaming.
#pragma once

#include <assimp/DefaultIOSystem.h>

#include <memory>
#include <string>

namespace rayview::model {

class CheckedWriteIOSystem : public Assimp::DefaultIOSystem {
 public:
  Assimp::IOStream* Open(const char* file, const char* mode = "wb") override;
  void Close(Assimp::IOStream* stream) override;
  // "PATH: reason" of the first write that failed, "" when every file was written whole.
  const std::string& failure() const { return *failure_; }

 private:
  std::shared_ptr<std::string> failure_ = std::make_shared<std::string>();
};

}  // namespace rayview::model
