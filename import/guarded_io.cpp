#include "guarded_io.h"

#include <sys/stat.h>

#include <cstring>

#include "rayview/input_files.h"

namespace rayview::model {

bool GuardedIOSystem::Exists(const char* file) const {
  struct stat info {};
  return ::stat(file, &info) == 0;  // a non-regular file exists, so that Open refuses it by name
}

Assimp::IOStream* GuardedIOSystem::Open(const char* file, const char* mode) {
  struct stat info {};
  const bool writing = std::strchr(mode, 'w') != nullptr || std::strchr(mode, 'a') != nullptr;
  if (!writing && ::stat(file, &info) == 0 && !S_ISREG(info.st_mode)) {
    if (refused_.empty()) refused_ = file;
    return nullptr;
  }
  Assimp::IOStream* stream = Assimp::DefaultIOSystem::Open(file, mode);
  if (stream && !writing) {
    opened_.push_back(file);
    rememberInput(file, "a file the model names");
  }
  return stream;
}

}  // namespace rayview::model
