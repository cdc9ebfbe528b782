#include "wire_format.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <limits>
#include <type_traits>

#include "rayview/scene_codec.h"

namespace rayview::wire {
namespace {

// The largest blob accepted: far above any scene rayview can render, far below what a garbage length reads as.
constexpr std::uint64_t kMaxBlobBytes = 64ULL << 30;

class Writer {
 public:
  explicit Writer(std::FILE* out) : out_(out) {}
  void raw(const void* data, std::size_t bytes) {
    if (ok_ && bytes > 0) ok_ = std::fwrite(data, 1, bytes, out_) == bytes;
  }
  void u32(std::uint32_t value) { raw(&value, sizeof value); }
  void blob(const void* data, std::size_t bytes) {
    const std::uint64_t size = bytes;
    raw(&size, sizeof size);
    raw(data, bytes);
  }
  void text(const std::string& s) { blob(s.data(), s.size()); }
  template <class T>
  void array(const std::vector<T>& items) {
    static_assert(std::is_trivially_copyable_v<T>);
    blob(items.data(), items.size() * sizeof(T));
  }
  bool finish() {
    raw(kEnd, sizeof kEnd);
    return ok_ && std::fflush(out_) == 0;
  }

 private:
  std::FILE* out_;
  bool ok_ = true;
};

void header(Writer& w, Kind kind) {
  w.raw(kMagic, sizeof kMagic);
  w.u32(static_cast<std::uint32_t>(kind));
}

class Reader {
 public:
  explicit Reader(int fd) : fd_(fd) {}
  bool raw(void* into, std::size_t bytes) {
    auto* at = static_cast<char*>(into);
    while (bytes > 0) {
      const ssize_t got = ::read(fd_, at, bytes);
      if (got < 0 && errno == EINTR) continue;
      if (got <= 0) return false;
      at += got;
      bytes -= static_cast<std::size_t>(got);
    }
    return true;
  }
  bool size(std::uint64_t& bytes) { return raw(&bytes, sizeof bytes) && bytes <= kMaxBlobBytes; }
  bool text(std::string& s) {
    std::uint64_t bytes = 0;
    if (!size(bytes) || bytes > (1ULL << 30)) return false;
    s.resize(bytes);
    return raw(s.data(), s.size());
  }
  template <class T>
  bool array(std::vector<T>& items) {
    std::uint64_t bytes = 0;
    if (!size(bytes) || bytes % sizeof(T) != 0) return false;
    items.resize(bytes / sizeof(T));
    return raw(items.data(), bytes);
  }

 private:
  int fd_;
};

// One blob of the scene codec (rayview/scene_codec.h), decoded by `decode` (decodeParameters or decodeGeometry) into
// `out`; false when it is cut short, malformed, or longer than what it decodes.
template <class Value, class Decode>
bool readCodecBlob(Reader& r, Decode decode, Value& out) {
  std::vector<std::uint8_t> bytes;
  if (!r.array(bytes)) return false;
  try {
    std::size_t at = 0;
    out = decode(bytes.data(), bytes.size(), at);
    return at == bytes.size();
  } catch (const CodecError&) {
    return false;
  }
}

// "role NUL path NUL ..." back into its pairs; false when the pairs do not close.
bool splitFilesRead(const std::string& text, std::vector<RememberedInput>& out) {
  std::vector<std::string> parts;
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t end = text.find('\0', at);
    if (end == std::string::npos) return false;
    parts.push_back(text.substr(at, end - at));
    at = end + 1;
  }
  if (parts.size() % 2 != 0) return false;
  for (std::size_t i = 0; i < parts.size(); i += 2) out.push_back({parts[i], parts[i + 1]});
  return true;
}

}  // namespace

bool writeScene(std::FILE* out, const SceneMessage& m) {
  Writer w(out);
  header(w, Kind::Scene);
  std::vector<std::uint8_t> parameters;
  encodeParameters(m.parameters, parameters);
  w.array(parameters);
  w.text(m.summary);
  std::string warnings;
  for (const std::string& warning : m.warnings) warnings.append(warning).push_back('\n');
  w.text(warnings);
  std::vector<std::uint8_t> geometry;
  encodeGeometry(m.geometry, geometry);
  w.array(geometry);
  std::string files;  // role NUL path NUL: a path may hold any byte but NUL
  for (const RememberedInput& file : m.filesRead)
    files.append(file.role).append(1, '\0').append(file.path).append(1, '\0');
  w.text(files);
  return w.finish();
}

bool writeError(std::FILE* out, const std::string& message) {
  Writer w(out);
  header(w, Kind::Error);
  w.text(message);
  return w.finish();
}

bool writeDone(std::FILE* out, const std::string& summary) {
  Writer w(out);
  header(w, Kind::Done);
  w.text(summary);
  return w.finish();
}

std::string readMessage(int fd, Kind& kind, SceneMessage& m, std::string& error) {
  Reader r(fd);
  char magic[sizeof kMagic];
  if (!r.raw(magic, sizeof magic)) return "no answer";
  if (std::memcmp(magic, kMagic, sizeof magic) != 0) return "not an import answer";
  std::uint32_t k = 0;
  if (!r.raw(&k, sizeof k)) return "truncated answer";
  kind = static_cast<Kind>(k);
  if (kind == Kind::Error) {
    if (!r.text(error)) return "truncated answer";
  } else if (kind == Kind::Done) {
    if (!r.text(m.summary)) return "truncated answer";
  } else if (kind == Kind::Scene) {
    std::string warnings, files;
    if (!readCodecBlob(r, decodeParameters, m.parameters) || !r.text(m.summary) || !r.text(warnings) ||
        !readCodecBlob(r, decodeGeometry, m.geometry) || !r.text(files))
      return "truncated or malformed answer";
    if (!splitFilesRead(files, m.filesRead)) return "malformed list of files read";
    for (std::size_t at = 0; at < warnings.size();) {
      const std::size_t end = warnings.find('\n', at);
      if (end == std::string::npos) break;
      m.warnings.push_back(warnings.substr(at, end - at));
      at = end + 1;
    }
  } else {
    return "unknown answer kind";
  }
  char end[sizeof kEnd];
  if (!r.raw(end, sizeof end) || std::memcmp(end, kEnd, sizeof end) != 0) return "truncated answer";
  return {};
}

}  // namespace rayview::wire
