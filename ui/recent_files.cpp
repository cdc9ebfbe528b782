#include "recent_files.h"

#include <algorithm>
#include <cstdlib>
#include <sstream>
#include <system_error>

#include "rayview/file_read.h"
#include "rayview/image.h"
#include "rayview/input_files.h"

namespace rayview {

namespace fs = std::filesystem;

RecentFiles::RecentFiles(fs::path storage) : storage_(std::move(storage)) {
  if (storage_.empty()) return;
  // Through the one reader of user files: a FIFO or /dev/zero in its place is refused at once, not read forever.
  const detail::UserFileRead read = detail::readUserFile(storage_, kMaxRecentFilesBytes, {}, kRecentFilesRole);
  std::istringstream in(read.bytes);
  std::string line;
  while (std::getline(in, line) && paths_.size() < kMaxRecentFiles)
    if (!line.empty() && std::find(paths_.begin(), paths_.end(), line) == paths_.end()) paths_.push_back(line);
}

fs::path RecentFiles::defaultStorage() {
  if (const char* config = std::getenv("XDG_CONFIG_HOME"); config && *config)
    return fs::path(config) / "rayview" / "recent.txt";
  if (const char* home = std::getenv("HOME"); home && *home)
    return fs::path(home) / ".config" / "rayview" / "recent.txt";
  return {};
}

bool RecentFiles::add(const std::string& path) {
  if (path.empty()) return true;
  std::error_code ec;
  const fs::path absolute = fs::absolute(path, ec);
  const std::string entry = ec ? path : absolute.lexically_normal().string();
  paths_.erase(std::remove(paths_.begin(), paths_.end(), entry), paths_.end());
  paths_.insert(paths_.begin(), entry);
  if (paths_.size() > kMaxRecentFiles) paths_.resize(kMaxRecentFiles);
  return save();
}

bool RecentFiles::save() const {
  if (storage_.empty()) return false;
  std::string text;
  for (const std::string& p : paths_) text += p + "\n";
  std::error_code ec;
  fs::create_directories(storage_.parent_path(), ec);
  try {
    // The list may replace itself (and only itself); a symlinked list is written through its link.
    writeFileAtomically(storage_, text, kRecentFilesRole);
  } catch (const ImageIoError&) {
    return false;  // a read-only home must not stop the viewer
  }
  return true;
}

}  // namespace rayview
