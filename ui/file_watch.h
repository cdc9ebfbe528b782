#pragma once
// Noticing that the open scene file changed on disk: its modification time and size, looked at no more
// than twice a second from the UI loop (one stat() call; cheap enough that no watcher thread is needed).

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>

namespace rayview {

inline constexpr std::chrono::milliseconds kFileWatchInterval{500};

class FileWatch {
 public:
  // Starts watching `path` as it is now; an empty path watches nothing.
  void watch(const std::filesystem::path& path);
  void stop() { path_.clear(); }

  // True once per change (new modification time or size) seen since the last call that returned true.
  // Does nothing until the interval has passed since the last look.
  bool changed(std::chrono::steady_clock::time_point now);

  // How long the UI may sleep before the next look is due.
  double secondsUntilNextLook(std::chrono::steady_clock::time_point now) const;
  bool active() const { return !path_.empty(); }
  const std::filesystem::path& path() const { return path_; }

 private:
  struct Stamp {
    std::filesystem::file_time_type modified;
    std::uintmax_t size = 0;
    bool operator==(const Stamp&) const = default;
  };
  static std::optional<Stamp> stampOf(const std::filesystem::path& path);

  std::filesystem::path path_;
  std::optional<Stamp> stamp_;
  std::chrono::steady_clock::time_point lastLook_{};
};

}  // namespace rayview
