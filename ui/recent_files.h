#pragma once
// The scenes opened lately, newest first, kept in $XDG_CONFIG_HOME/rayview/recent.txt (or
// ~/.config/rayview/recent.txt), one absolute path per line.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace rayview {

inline constexpr std::size_t kMaxRecentFiles = 12;
// A longer file is not a list rayview wrote: it is read as an empty list.
inline constexpr std::uintmax_t kMaxRecentFilesBytes = 1 << 20;

class RecentFiles {
 public:
  // Reads the list from `storage` (a missing or unreadable file, or one that is not a regular file, is an empty
  // list).
  explicit RecentFiles(std::filesystem::path storage);

  // Where the list lives by default; empty when neither XDG_CONFIG_HOME nor HOME is set.
  static std::filesystem::path defaultStorage();

  const std::vector<std::string>& paths() const { return paths_; }
  const std::filesystem::path& storage() const { return storage_; }

  // Moves `path` (made absolute) to the front and saves. Returns false when saving failed.
  bool add(const std::string& path);

 private:
  bool save() const;

  std::filesystem::path storage_;
  std::vector<std::string> paths_;
};

}  // namespace rayview
