#pragma once
// Reading a file the user named (a scene, a texture image): never blocks, never reads past a limit, and
// says what the file is when it is not what was expected, so a wrong path gives a message, not a hang.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

namespace rayview::detail {

struct UserFileRead {
  std::string bytes;    // the whole file when `problem` is empty
  std::string problem;  // "" on success, else why not, to follow the file name: "is a directory", ...
  bool notFound = false;
};

// What a file read is recorded as (rayview/input_files.h) when its reader names no role.
inline constexpr std::string_view kInputRole = "a file this command reads";

// How many bytes `checkStart` sees before the rest of the file is read.
inline constexpr std::size_t kFileStartBytes = 64 * 1024;

// A file the user named, opened with readUserFile's checks but not read: for readers that take it in pieces
// (the scene loader's block stream) rather than hold it whole.
class UserFile {
 public:
  // Opens `path` as readUserFile does (regular files only, never a blocking open, at most `maxBytes`); on
  // failure `problem()` says why, as readUserFile's `problem` would. A file found is recorded as `role`
  // (rayview/input_files.h) whether or not it can then be read, so no output replaces it.
  UserFile(const std::filesystem::path& path, std::uintmax_t maxBytes, std::string_view role = kInputRole);
  ~UserFile();
  UserFile(const UserFile&) = delete;
  UserFile& operator=(const UserFile&) = delete;

  const std::string& problem() const { return problem_; }
  bool notFound() const { return notFound_; }
  std::uintmax_t size() const { return size_; }  // at the open
  // Up to `count` bytes at `offset` (fewer only at the end of the file); -1 on a read error (errno set).
  long read(std::uintmax_t offset, char* into, std::size_t count) const;

 private:
  // The problem, "" when open.
  std::string open(const std::filesystem::path& path, std::uintmax_t maxBytes, std::string_view role);

  int fd_ = -1;
  std::uintmax_t size_ = 0;
  bool notFound_ = false;
  std::string problem_;  // after the members open() sets
};

// Reads `path` whole. Refuses, without opening it for a blocking read, anything but a regular file (a
// directory, a FIFO, a device, a socket): stat first, open with O_NONBLOCK, fstat the open descriptor and
// check it is the same regular file. Refuses a file larger than `maxBytes` from its size before reading,
// and stops reading at the limit should the file grow meanwhile. `checkStart`, when given, sees the first
// bytes (at most kFileStartBytes) and can refuse the file before the rest is read by returning a problem.
// A file found is recorded as `role` (UserFile).
UserFileRead readUserFile(const std::filesystem::path& path, std::uintmax_t maxBytes,
                          const std::function<std::string(std::string_view start)>& checkStart = {},
                          std::string_view role = kInputRole);

// What a file's first bytes say it is when it cannot be the text of a scene: "is a PNG image, not a scene
// file", "is UTF-16 text; save it as UTF-8". "" when it may be text (NUL bytes are the caller's check,
// which can give their line).
std::string binaryFileKind(std::string_view start);

// "2.0 GiB", "512 MiB", "12 bytes": sizes as messages show them.
std::string describeSize(std::uintmax_t bytes);

// Are the two paths the same file (same device and inode; any spelling, hard link or symlink)? False when
// either does not exist.
bool sameFile(const std::filesystem::path& a, const std::filesystem::path& b);

}  // namespace rayview::detail
