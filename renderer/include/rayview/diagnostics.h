#pragma once
// Located messages about a scene file: warnings for what was repaired or ignored, errors for what cannot be.

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace rayview {

enum class Severity { Warning, Error };

struct SourceLocation {
  std::string file;  // as the user named it
  int line = 0;      // 1-based; 0 when the message is about the whole file
};

struct Diagnostic {
  Severity severity = Severity::Warning;
  SourceLocation where;
  std::string message;

  // "scene.xml:12: warning: ..." (the form compilers use, so editors can jump to it).
  std::string format() const;
};

// The one exception type for bad scene input. Thrown by the loader, caught once by the command line or viewer.
class SceneError : public std::runtime_error {
 public:
  explicit SceneError(Diagnostic diagnostic);
  const Diagnostic& diagnostic() const { return diagnostic_; }

 private:
  Diagnostic diagnostic_;
};

[[noreturn]] void throwSceneError(const SourceLocation& where, const std::string& message);

// "1 camera", "2 cameras": a count and its noun, as messages and summaries print them.
inline std::string counted(std::size_t count, const std::string& singular) {
  return std::to_string(count) + " " + singular + (count == 1 ? "" : "s");
}

}  // namespace rayview
