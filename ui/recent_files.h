#pragma once
// The scenes opened lately, newest first, kept in $XDG_CONFIG_HOME/rayview/recent.txt (or
// ~/.config/rayview/recent.txt), one absolute path per line.

#include <filesystem>
#include <string>
#include <vector>

namespace rayview {

inline constexpr std::size_t kMaxRecentFiles = 12;

class RecentFiles {
 public:
  // Reads the list from `storage` (a missing or unreadable file is an empty list).
  explicit RecentFiles(std::filesystem::path storage);

  // Where the list lives by default; empty when neither XDG_CONFIG_HOME nor HOME is set.
  static std::filesystem::path defaultStorage();

  const std::vector<std::string>& paths() const { return paths_; }

  // Moves `path` (made absolute) to the front and saves. Returns false when saving failed.
  bool add(const std::string& path);

 private:
  bool save() const;

  std::filesystem::path storage_;
  std::vector<std::string> paths_;
};

}  // namespace rayview
