#include "recovery_file.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <system_error>
#include <utility>

#include "rayview/file_read.h"
#include "rayview/image.h"
#include "rayview/scene_loader.h"
#include "rayview/scene_writer.h"
#include "scene_session.h"

namespace rayview {

namespace fs = std::filesystem;

namespace {

constexpr std::uintmax_t kMaxRecoveryBytes = 16u << 20;  // parameters only: kilobytes, even with many materials
constexpr std::string_view kHeader = "<!-- rayview recovery of: ";
constexpr std::string_view kHeaderEnd = " -->";

// The scene's path inside an XML comment: '%', '-' and '>' (and control bytes) as %XX, so no path ends it early.
std::string encodePath(const std::string& path) {
  std::string out;
  for (const unsigned char c : path) {
    if (c == '%' || c == '-' || c == '>' || c < 0x20) {
      char hex[4];
      std::snprintf(hex, sizeof hex, "%%%02X", c);
      out += hex;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out;
}

std::string decodePath(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '%' && i + 2 < text.size()) {
      out += static_cast<char>(std::strtol(text.substr(i + 1, 2).c_str(), nullptr, 16));
      i += 2;
    } else {
      out += text[i];
    }
  }
  return out;
}

std::uint64_t fnv1a(const std::string& text) {
  std::uint64_t h = 14695981039346656037ull;
  for (const unsigned char c : text) h = (h ^ c) * 1099511628211ull;
  return h;
}

}  // namespace

fs::path recoveryDirectory() {
  if (const char* dir = std::getenv("RAYVIEW_RECOVERY_DIR"); dir && *dir) return fs::path(dir);
  if (const char* state = std::getenv("XDG_STATE_HOME"); state && *state) return fs::path(state) / "rayview";
  if (const char* home = std::getenv("HOME"); home && *home) return fs::path(home) / ".local" / "state" / "rayview";
  return {};
}

fs::path recoveryFileFor(const std::string& scenePath) {
  const fs::path dir = recoveryDirectory();
  if (dir.empty()) return {};
  std::error_code ec;
  const std::string absolute = scenePath.empty() ? std::string() : fs::absolute(scenePath, ec).lexically_normal().string();
  const std::string stem = scenePath.empty() ? std::string("default") : fs::path(scenePath).stem().string();
  char hash[20];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(fnv1a(absolute)));
  return dir / (stem + "-" + hash + ".recovery.xml");
}

void writeRecoveryFile(const fs::path& file, const std::string& scenePath, const SceneParameters& edits) {
  std::error_code ec;
  fs::create_directories(file.parent_path(), ec);
  const std::string xml = std::string(kHeader) + encodePath(scenePath) + std::string(kHeaderEnd) + "\n" +
                          sceneToXml(edits, SceneGeometry{}, std::string());
  writeFileAtomically(file, xml, kRecoveryRole);
}

std::optional<RecoveredEdits> readRecoveryFile(const fs::path& file) {
  const detail::UserFileRead read = detail::readUserFile(file, kMaxRecoveryBytes, {}, kRecoveryRole);
  if (read.notFound) return std::nullopt;
  const auto fail = [&](const std::string& why) {
    Diagnostic d;
    d.severity = Severity::Error;
    d.where.file = file.string();
    d.message = why;
    return SceneError(std::move(d));
  };
  if (!read.problem.empty()) throw fail(read.problem);
  const std::size_t lineEnd = read.bytes.find('\n');
  const std::string first = read.bytes.substr(0, lineEnd);
  if (first.rfind(kHeader, 0) != 0 || first.size() < kHeader.size() + kHeaderEnd.size() ||
      first.compare(first.size() - kHeaderEnd.size(), kHeaderEnd.size(), kHeaderEnd) != 0)
    throw fail("not a rayview recovery file (its first line does not name the scene)");
  RecoveredEdits r;
  r.scenePath = decodePath(first.substr(kHeader.size(), first.size() - kHeader.size() - kHeaderEnd.size()));
  LoadOptions options;
  options.loadTexture = false;
  r.edits = loadSceneText(read.bytes, file.string(), file.parent_path(), options).scene.parameters();
  std::error_code ec;
  r.written = fs::last_write_time(file, ec);
  return r;
}

std::string recoveryMismatch(const SceneParameters& recovered, const SceneParameters& loaded) {
  if (recovered.materials.size() != loaded.materials.size())
    return "the scene has " + std::to_string(loaded.materials.size()) + " materials now, the edits " +
           std::to_string(recovered.materials.size());
  for (std::size_t i = 0; i < loaded.materials.size(); ++i)
    if (recovered.materials[i].id != loaded.materials[i].id)
      return "material " + loaded.materials[i].id + " is not where the edits have it";
  if (recovered.lights.of<PointLight>().size() != loaded.lights.of<PointLight>().size() ||
      recovered.lights.of<TriangularLight>().size() != loaded.lights.of<TriangularLight>().size())
    return "the scene's lights are not those the edits were made to";
  return {};
}

std::string RecoveryKeeper::keep(const SceneSession* session, const std::string& scenePath, bool paused,
                                 Clock::time_point now) {
  if (paused || !session) return {};
  const fs::path file = recoveryFileFor(scenePath);
  if (file.empty()) return {};
  if (!session->unsaved()) {
    // Nothing to keep: undone back or saved. Only a file this process wrote goes; another's waits for its offer.
    dueAt_.reset();
    if (written_) {
      std::error_code ec;
      fs::remove(file, ec);
      written_.reset();
    }
    return {};
  }
  const SceneParameters& edits = session->committedEdits();
  if (written_ && *written_ == edits) {
    dueAt_.reset();
    return {};
  }
  if (!dueAt_) dueAt_ = std::max(now, lastWrite_ + kRecoveryInterval);
  if (now < *dueAt_) return {};
  dueAt_.reset();
  lastWrite_ = now;
  try {
    writeRecoveryFile(file, scenePath, edits);
    written_ = edits;
    lastProblem_.clear();
  } catch (const std::exception& e) {
    // Said once, not at every attempt: a full disk or a read-only home must not flood the terminal.
    const std::string problem = std::string("unsaved edits not kept for recovery: ") + e.what();
    if (problem == lastProblem_) return {};
    lastProblem_ = problem;
    return problem;
  }
  return {};
}

fs::path RecoveryKeeper::keepNow(const SceneSession* session, const std::string& scenePath, std::string& problem) {
  const fs::path file = recoveryFileFor(scenePath);
  if (!session || !session->unsaved() || file.empty()) return {};
  try {
    if (!written_ || !(*written_ == session->committedEdits())) writeRecoveryFile(file, scenePath, session->committedEdits());
    written_ = session->committedEdits();
    return file;
  } catch (const std::exception& e) {
    problem = e.what();
    return {};
  }
}

std::optional<double> RecoveryKeeper::secondsUntilDue(Clock::time_point now) const {
  if (!dueAt_) return std::nullopt;
  return std::max(0.0, std::chrono::duration<double>(*dueAt_ - now).count());
}

void RecoveryKeeper::discard(const std::string& scenePath) {
  if (!written_) return;
  std::error_code ec;
  fs::remove(recoveryFileFor(scenePath), ec);
  written_.reset();
}

}  // namespace rayview
