// Files written whole or not at all: a temporary file beside the output, renamed into place; removed by the
// signals that would end the process mid-write.
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>
#include <random>
#include <string_view>

#include "rayview/image.h"
#include "rayview/input_files.h"

namespace rayview {
namespace {

// One write at a time registers its temporary file here (the command line writes one file at a time).
char g_temporaryPath[PATH_MAX];
std::atomic<bool> g_temporaryActive{false};

// The bytes of a temporary name beyond the output's own: ".tmp-" and 8 hexadecimal digits.
constexpr std::size_t kTemporarySuffixBytes = 13;
// The output's name is cut to this many bytes in the temporary name, so that name fits NAME_MAX whatever the
// output's own length (a legal name of up to NAME_MAX bytes plus a suffix would not).
constexpr std::size_t kTemporaryStemBytes = 64;
static_assert(kTemporaryStemBytes + kTemporarySuffixBytes <= NAME_MAX);

// The file a write to `path` replaces: a symlink's final target (so the link stays a link), else `path`.
std::filesystem::path throughSymlinks(std::filesystem::path path) {
  for (int hops = 0; hops < 40; ++hops) {
    std::error_code ec;
    if (!std::filesystem::is_symlink(std::filesystem::symlink_status(path, ec)) || ec) return path;
    std::filesystem::path target = std::filesystem::read_symlink(path, ec);
    if (ec) return path;
    path = target.is_absolute() ? target : path.parent_path() / target;
  }
  return path;  // a loop of links: the rename reports nothing better than open() would
}

std::filesystem::path temporaryNameFor(const std::filesystem::path& path, unsigned number) {
  const std::string name = path.filename().string();
  char suffix[kTemporarySuffixBytes + 1];
  std::snprintf(suffix, sizeof suffix, ".tmp-%08x", number);
  return path.parent_path() / (name.substr(0, kTemporaryStemBytes) + suffix);
}

// Creates the temporary file (never an existing one) and registers it for the signal handlers; -1 on failure.
int createTemporary(const std::filesystem::path& target, std::filesystem::path& temporary, bool& registered) {
  std::random_device random;
  for (int attempt = 0; attempt < 16; ++attempt) {
    temporary = temporaryNameFor(target, random());
    // Registered before the file exists, cleared after it is renamed or removed.
    registered = temporary.native().size() < sizeof g_temporaryPath && !g_temporaryActive.load();
    if (registered) {
      std::memcpy(g_temporaryPath, temporary.c_str(), temporary.native().size() + 1);
      g_temporaryActive.store(true);
    }
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOCTTY, 0666);
    if (fd >= 0 || errno != EEXIST) return fd;
    if (registered) g_temporaryActive.store(false);
    registered = false;
  }
  return -1;
}

bool writeAll(int fd, std::string_view bytes) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t wrote = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (wrote < 0 && errno == EINTR) continue;
    if (wrote <= 0) return false;
    done += static_cast<std::size_t>(wrote);
  }
  return true;
}

bool writeAll(int fd, const FileBytes& bytes) {
  for (std::string_view piece : bytes.pieces)
    if (!writeAll(fd, piece)) return false;
  return true;
}

}  // namespace

const char* temporaryFileInProgress() { return g_temporaryActive.load() ? g_temporaryPath : nullptr; }

FileBytes FileBytes::viewOf(const std::string& bytes) {
  FileBytes view;
  view.pieces.push_back(bytes);
  return view;
}

std::size_t FileBytes::size() const {
  std::size_t total = 0;
  for (std::string_view piece : pieces) total += piece.size();
  return total;
}

std::string FileBytes::joined() const {
  std::string bytes;
  bytes.reserve(size());
  for (std::string_view piece : pieces) bytes += piece;
  return bytes;
}

void writeFileAtomically(const std::filesystem::path& path, const std::string& bytes, std::string_view mayReplaceRole) {
  writeFileAtomically(path, FileBytes::viewOf(bytes), mayReplaceRole);
}

void writeFileAtomically(const std::filesystem::path& path, const FileBytes& bytes, std::string_view mayReplaceRole) {
  if (const std::string problem = outputReplacesInput(path, mayReplaceRole); !problem.empty())
    throw ImageIoError(problem);
  const std::filesystem::path target = throughSymlinks(path);
  std::filesystem::path temporary;
  bool registered = false;
  const int fd = createTemporary(target, temporary, registered);
  struct Unregister {
    const bool& registered;
    ~Unregister() {
      if (registered) g_temporaryActive.store(false);
    }
  } unregister{registered};
  if (fd < 0) throw ImageIoError("cannot write " + path.string() + ": " + std::strerror(errno));
  const bool written = writeAll(fd, bytes);
  int error = errno;
  const bool closed = ::close(fd) == 0;
  if (!closed && written) error = errno;
  if (!written || !closed) {
    ::unlink(temporary.c_str());
    throw ImageIoError("cannot write " + path.string() + ": " + std::strerror(error));
  }
  if (::rename(temporary.c_str(), target.c_str()) != 0) {
    error = errno;
    ::unlink(temporary.c_str());
    throw ImageIoError("cannot write " + path.string() + ": " + std::strerror(error));
  }
}

}  // namespace rayview
