#include "file_watch.h"

#include <algorithm>
#include <system_error>

namespace rayview {

std::optional<FileWatch::Stamp> FileWatch::stampOf(const std::filesystem::path& path) {
  std::error_code ec;
  Stamp stamp;
  stamp.modified = std::filesystem::last_write_time(path, ec);
  if (ec) return std::nullopt;
  stamp.size = std::filesystem::file_size(path, ec);
  if (ec) return std::nullopt;
  return stamp;
}

void FileWatch::watch(const std::filesystem::path& path) {
  path_ = path;
  stamp_ = path.empty() ? std::nullopt : stampOf(path);
  lastLook_ = std::chrono::steady_clock::now();
}

bool FileWatch::changed(std::chrono::steady_clock::time_point now) {
  if (path_.empty() || now - lastLook_ < kFileWatchInterval) return false;
  lastLook_ = now;
  const std::optional<Stamp> stamp = stampOf(path_);
  // A file that is briefly missing (an editor saving by rename) is not a change; its reappearance is.
  if (!stamp || stamp == stamp_) return false;
  stamp_ = stamp;
  return true;
}

double FileWatch::secondsUntilNextLook(std::chrono::steady_clock::time_point now) const {
  if (path_.empty()) return 3600.0;
  const double left = std::chrono::duration<double>(lastLook_ + kFileWatchInterval - now).count();
  return std::max(left, 0.0);
}

}  // namespace rayview
