#include "rayview/file_read.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "rayview/input_files.h"

namespace rayview::detail {

namespace {

std::string notAFile(const struct stat& st) {
  if (S_ISDIR(st.st_mode)) return "is a directory, not a file";
  if (S_ISFIFO(st.st_mode)) return "is a named pipe (FIFO), not a regular file";
  if (S_ISCHR(st.st_mode)) return "is a character device, not a regular file";
  if (S_ISBLK(st.st_mode)) return "is a block device, not a regular file";
  if (S_ISSOCK(st.st_mode)) return "is a socket, not a regular file";
  if (!S_ISREG(st.st_mode)) return "is not a regular file";
  return {};
}

bool startsWith(std::string_view s, std::string_view prefix) { return s.substr(0, prefix.size()) == prefix; }

}  // namespace

std::string describeSize(std::uintmax_t bytes) {
  char buffer[64];
  if (bytes >= (1ULL << 30)) std::snprintf(buffer, sizeof buffer, "%.1f GiB", static_cast<double>(bytes) / (1ULL << 30));
  else if (bytes >= (1ULL << 20)) std::snprintf(buffer, sizeof buffer, "%.1f MiB", static_cast<double>(bytes) / (1ULL << 20));
  else std::snprintf(buffer, sizeof buffer, "%ju bytes", bytes);
  return buffer;
}

UserFile::UserFile(const std::filesystem::path& path, std::uintmax_t maxBytes, std::string_view role)
    : problem_(open(path, maxBytes, role)) {}

std::string UserFile::open(const std::filesystem::path& path, std::uintmax_t maxBytes, std::string_view role) {
  struct stat named {};
  if (::stat(path.c_str(), &named) != 0) {
    notFound_ = errno == ENOENT || errno == ENOTDIR;
    return std::string("cannot be opened: ") + std::strerror(errno);
  }
  rememberInput(path, role);
  if (std::string problem = notAFile(named); !problem.empty()) return problem;
  if (static_cast<std::uintmax_t>(named.st_size) > maxBytes)
    return "is too large (" + describeSize(static_cast<std::uintmax_t>(named.st_size)) + "; the limit is " +
           describeSize(maxBytes) + ")";

  // O_NONBLOCK: should the path have become a FIFO since the stat, open() still returns at once.
  fd_ = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd_ < 0) return std::string("cannot be opened: ") + std::strerror(errno);
  struct stat opened {};
  if (::fstat(fd_, &opened) != 0) return std::string("cannot be read: ") + std::strerror(errno);
  if (std::string problem = notAFile(opened); !problem.empty()) return problem;
  if (opened.st_dev != named.st_dev || opened.st_ino != named.st_ino)
    return "changed while it was being opened; try again";
  const int flags = ::fcntl(fd_, F_GETFL);
  if (flags >= 0) ::fcntl(fd_, F_SETFL, flags & ~O_NONBLOCK);
  size_ = static_cast<std::uintmax_t>(opened.st_size);
  if (size_ > maxBytes)
    return "is too large (" + describeSize(size_) + "; the limit is " + describeSize(maxBytes) + ")";
  return {};
}

UserFile::~UserFile() {
  if (fd_ >= 0) ::close(fd_);
}

long UserFile::read(std::uintmax_t offset, char* into, std::size_t count) const {
  std::size_t done = 0;
  while (done < count) {
    const ssize_t got = ::pread(fd_, into + done, count - done, static_cast<off_t>(offset + done));
    if (got < 0) {
      if (errno == EINTR) continue;
      return -1;
    }
    if (got == 0) break;
    done += static_cast<std::size_t>(got);
  }
  return static_cast<long>(done);
}

UserFileRead readUserFile(const std::filesystem::path& path, std::uintmax_t maxBytes,
                          const std::function<std::string(std::string_view start)>& checkStart, std::string_view role) {
  UserFileRead out;
  auto fail = [&](std::string problem) {
    out.bytes.clear();
    out.problem = std::move(problem);
    return std::move(out);
  };
  const UserFile file(path, maxBytes, role);
  if (!file.problem().empty()) {
    out.notFound = file.notFound();
    return fail(file.problem());
  }
  out.bytes.reserve(static_cast<std::size_t>(file.size()));
  bool checked = !checkStart;
  char buffer[kFileStartBytes];
  while (true) {
    const long got = file.read(out.bytes.size(), buffer, sizeof buffer);
    if (got < 0) return fail(std::string("cannot be read: ") + std::strerror(errno));
    if (got == 0) break;
    if (out.bytes.size() + static_cast<std::size_t>(got) > maxBytes)
      return fail("is too large (it grew past the limit of " + describeSize(maxBytes) + " while being read)");
    out.bytes.append(buffer, static_cast<std::size_t>(got));
    if (!checked && out.bytes.size() >= kFileStartBytes) {
      checked = true;
      if (std::string problem = checkStart(out.bytes); !problem.empty()) return fail(problem);
    }
  }
  if (!checked)
    if (std::string problem = checkStart(out.bytes); !problem.empty()) return fail(problem);
  return out;
}

std::string binaryFileKind(std::string_view start) {
  struct Signature {
    std::string_view bytes;
    const char* kind;
  };
  static constexpr Signature kSignatures[] = {
      {"\x89PNG\r\n\x1a\n", "a PNG image"},
      {"\xFF\xD8\xFF", "a JPEG image"},
      {"GIF87a", "a GIF image"},
      {"GIF89a", "a GIF image"},
      {"%PDF-", "a PDF document"},
      {std::string_view("PK\x03\x04", 4), "a ZIP archive"},
      {"\x1F\x8B", "a gzip-compressed file"},
      {"\x7F" "ELF", "an executable (ELF)"},
  };
  for (const Signature& s : kSignatures)
    if (startsWith(start, s.bytes)) return std::string("is ") + s.kind + ", not a scene file";
  if (startsWith(start, std::string_view("\xFF\xFE\0\0", 4)) || startsWith(start, std::string_view("\0\0\xFE\xFF", 4)))
    return "is UTF-32 text; save it as UTF-8";
  if (startsWith(start, "\xFF\xFE") || startsWith(start, "\xFE\xFF")) return "is UTF-16 text; save it as UTF-8";
  // UTF-16 without a byte order mark: ASCII characters alternate with NUL bytes.
  if (start.size() >= 4 && ((start[0] != '\0' && start[1] == '\0' && start[2] != '\0' && start[3] == '\0') ||
                            (start[0] == '\0' && start[1] != '\0' && start[2] == '\0' && start[3] != '\0')))
    return "is UTF-16 text; save it as UTF-8";
  return {};
}

bool sameFile(const std::filesystem::path& a, const std::filesystem::path& b) {
  struct stat sa {}, sb {};
  if (::stat(a.c_str(), &sa) != 0 || ::stat(b.c_str(), &sb) != 0) return false;
  return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

}  // namespace rayview::detail
