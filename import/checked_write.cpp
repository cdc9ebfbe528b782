#include "checked_write.h"

#include <assimp/IOStream.hpp>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace rayview::model {
namespace {

// A stdio file whose every failure lands in the shared `failure` text (the first one only).
class CheckedStream : public Assimp::IOStream {
 public:
  CheckedStream(std::FILE* file, std::string path, std::shared_ptr<std::string> failure)
      : file_(file), path_(std::move(path)), failure_(std::move(failure)) {}
  ~CheckedStream() override {
    if (std::fflush(file_) != 0) note();
    if (std::fclose(file_) != 0) note();
  }
  size_t Read(void* buffer, size_t size, size_t count) override { return std::fread(buffer, size, count, file_); }
  size_t Write(const void* buffer, size_t size, size_t count) override {
    const size_t written = std::fwrite(buffer, size, count, file_);
    if (written != count) note();
    return written;
  }
  aiReturn Seek(size_t offset, aiOrigin origin) override {
    const int whence = origin == aiOrigin_SET ? SEEK_SET : origin == aiOrigin_CUR ? SEEK_CUR : SEEK_END;
    return std::fseek(file_, static_cast<long>(offset), whence) == 0 ? aiReturn_SUCCESS : aiReturn_FAILURE;
  }
  size_t Tell() const override { return static_cast<size_t>(std::ftell(file_)); }
  size_t FileSize() const override {
    const long at = std::ftell(file_);
    std::fseek(file_, 0, SEEK_END);
    const long size = std::ftell(file_);
    std::fseek(file_, at, SEEK_SET);
    return static_cast<size_t>(size);
  }
  void Flush() override {
    if (std::fflush(file_) != 0) note();
  }

 private:
  void note() {
    if (failure_->empty()) *failure_ = path_ + ": " + std::strerror(errno ? errno : EIO);
  }
  std::FILE* file_;
  std::string path_;
  std::shared_ptr<std::string> failure_;
};

}  // namespace

Assimp::IOStream* CheckedWriteIOSystem::Open(const char* file, const char* mode) {
  std::FILE* opened = std::fopen(file, mode);
  if (!opened) {
    if (failure_->empty()) *failure_ = std::string(file) + ": " + std::strerror(errno);
    return nullptr;
  }
  return new CheckedStream(opened, file, failure_);
}

void CheckedWriteIOSystem::Close(Assimp::IOStream* stream) { delete stream; }

}  // namespace rayview::model
