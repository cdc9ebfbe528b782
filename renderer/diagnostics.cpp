#include "rayview/diagnostics.h"

namespace rayview {

std::string Diagnostic::format() const {
  std::string text = where.file;
  if (where.line > 0) {
    text.push_back(':');
    text.append(std::to_string(where.line));
  }
  text.append(severity == Severity::Error ? ": error: " : ": warning: ");
  text.append(message);
  return text;
}

SceneError::SceneError(Diagnostic diagnostic)
    : std::runtime_error(diagnostic.format()), diagnostic_(std::move(diagnostic)) {}

void throwSceneError(const SourceLocation& where, const std::string& message) {
  throw SceneError(Diagnostic{Severity::Error, where, message});
}

}  // namespace rayview
