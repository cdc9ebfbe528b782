#include "recovery_controller.h"

#include <cfloat>
#include <cstdio>
#include <ctime>
#include <system_error>

#include <imgui.h>

#include "rayview/diagnostics.h"
#include "scene_session.h"

namespace rayview {

namespace fs = std::filesystem;

namespace {

std::string describeTime(fs::file_time_type written) {
  const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::file_clock::to_sys(written));
  std::tm local{};
  localtime_r(&t, &local);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%d %H:%M:%S", &local);
  return text;
}

void say(const std::string& line) {
  std::printf("%s\n", line.c_str());
  std::fflush(stdout);
}

}  // namespace

void RecoveryController::sceneOpened(const std::string& scenePath) {
  keeper_.sceneReplaced();
  offer_.reset();
  const fs::path file = recoveryFileFor(scenePath);
  if (file.empty()) return;
  try {
    std::optional<RecoveredEdits> edits = readRecoveryFile(file);
    if (!edits) return;
    offer_ = Offer{file, std::move(*edits), {}, {}};
    offer_->when = describeTime(offer_->edits.written);
    say("recovery offered " + file.string() + " (unsaved edits of " +
        (scenePath.empty() ? std::string("the default scene") : scenePath) + " from " + offer_->when + ")");
  } catch (const SceneError& e) {
    // Left where it is: a file rayview cannot read is not deleted on the user's behalf.
    std::fprintf(stderr, "rayview: recovery file not offered: %s\n", e.diagnostic().format().c_str());
  }
}

void RecoveryController::keep(const SceneSession* session, const std::string& scenePath, Clock::time_point now) {
  if (const std::string problem = keeper_.keep(session, scenePath, offer_.has_value(), now); !problem.empty())
    std::fprintf(stderr, "rayview: %s\n", problem.c_str());
}

std::string RecoveryController::keepNow(const SceneSession* session, const std::string& scenePath) {
  // An offer still up: its file is left as it is (it holds the edits offered), and nothing new was kept.
  if (!offer_) {
    std::string problem;
    keeper_.keepNow(session, scenePath, problem);
    if (!problem.empty()) return "your unsaved edits could not be kept: " + problem;
  }
  return note(session, scenePath);
}

std::string RecoveryController::note(const SceneSession* session, const std::string& scenePath) const {
  if (offer_) return "the unsaved edits offered at the start are still kept in " + offer_->file.string();
  // Asked once per loop: the common case (nothing unsaved) looks at no path.
  if (!session || !session->unsaved()) return "there were no unsaved edits";
  const fs::path file = recoveryFileFor(scenePath);
  if (file.empty()) return "there were no unsaved edits";
  const std::optional<SceneParameters>& written = keeper_.written();
  if (!written) return "your unsaved edits could not be kept";
  // The file is written at most kRecoveryInterval after an edit: the last moment's edits may be missing.
  const char* which = *written == session->committedEdits() ? "your unsaved edits are" : "your unsaved edits but the last moment's are";
  return std::string(which) + " kept in " + file.string() + ", offered when you open the scene again";
}

std::string RecoveryController::answer(bool restore, SceneSession* session) {
  if (!offer_) return "no recovered edits are offered";
  if (restore) {
    if (!session) return "no scene to restore the edits into";
    if (std::string why = recoveryMismatch(offer_->edits.edits, session->loaded().parameters()); !why.empty()) {
      offer_->problem = "cannot restore: the scene file changed since (" + why + ")";
      return offer_->problem;
    }
    // Committed with the next frame's edits: one undo step back to the file, and unsaved until saved.
    session->edits() = offer_->edits.edits;
    offer_.reset();
    say("recovery restored");
    return {};
  }
  std::error_code ec;
  fs::remove(offer_->file, ec);
  offer_.reset();
  say("recovery discarded");
  return {};
}

std::optional<bool> RecoveryController::draw(float x, float y, float width) {
  buttons_.clear();
  if (!offer_) return std::nullopt;
  const auto rect = [] {
    const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
    char text[80];
    std::snprintf(text, sizeof text, "%.0f,%.0f,%.0f,%.0f", a.x, a.y, b.x - a.x, b.y - a.y);
    return std::string(text);
  };
  std::optional<bool> pressed;
  ImGui::SetNextWindowPos(ImVec2(x + 0.5f * width, y), ImGuiCond_Always, ImVec2(0.5f, 0.0f));
  ImGui::SetNextWindowSizeConstraints(ImVec2(0.0f, 0.0f), ImVec2(width, FLT_MAX));
  ImGui::PushStyleColor(ImGuiCol_WindowBg, ImVec4(0.12f, 0.2f, 0.35f, 0.96f));
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                                 ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings;
  if (ImGui::Begin("Unsaved edits were kept", nullptr, flags)) {
    ImGui::Text("A viewer that stopped on %s left unsaved edits (%s).",
                offer_->edits.scenePath.empty() ? "the default scene" : fs::path(offer_->edits.scenePath).filename().c_str(),
                offer_->when.c_str());
    if (!offer_->problem.empty()) ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "%s", offer_->problem.c_str());
    if (ImGui::Button("Restore them")) pressed = true;
    buttons_ = "restore=" + rect();
    ImGui::SameLine();
    if (ImGui::Button("Discard them")) pressed = false;
    buttons_ += " discard=" + rect();
  }
  ImGui::End();
  ImGui::PopStyleColor();
  return pressed;
}

}  // namespace rayview
