#pragma once
// Assimp's warnings and errors while it reads one file (private to rayview_import). Some say that it dropped broken
// parts and carried on (faces with out-of-range indices in glTF, OFF, LWO, ...); rayview refuses such files, as
// docs/scene-format.md says, instead of drawing what is left.

#include <memory>
#include <string>

namespace rayview::model {

class AssimpWarnings {
 public:
  AssimpWarnings();  // starts listening (one reading at a time: Assimp's logger is global)
  ~AssimpWarnings();
  AssimpWarnings(const AssimpWarnings&) = delete;
  AssimpWarnings& operator=(const AssimpWarnings&) = delete;

  // Assimp's message about broken data it dropped or repaired, or "" when there was none.
  std::string brokenData() const;

 private:
  struct Stream;
  std::unique_ptr<Stream> stream_;
};

}  // namespace rayview::model
