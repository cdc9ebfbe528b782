// The "Render" panel (settings that restart the render, and the display options that do not: stats, exposure,
// gamma) and the stats over the image (what it costs).
#include <algorithm>
#include <cstdio>
#include <iterator>
#include <string>

#include <imgui.h>

#include "panels.h"
#include "widgets.h"

namespace rayview {
namespace {

// Above this, a directional triangular light saturates a white diffuse surface facing it.
constexpr float kDirectionalIntensityLimit = 255.0f;

std::string formatted(const char* format, double value) {
  char text[64];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

// "412 MiB (peak 530 MiB)", or "-" where the kernel does not say.
std::string memoryText(std::uint64_t resident, std::uint64_t peak) {
  if (resident == 0) return "-";
  char text[64];
  std::snprintf(text, sizeof text, "%.0f MiB (peak %.0f MiB)", static_cast<double>(resident) / (1 << 20),
                static_cast<double>(peak) / (1 << 20));
  return text;
}

std::string millisecondsOrPending(double ms) {
  if (ms < 0.0) return "...";
  char text[32];
  std::snprintf(text, sizeof text, "%.1f ms", ms);
  return text;
}

// What the chosen triangular-light model does and the intensities it expects; a warning when the scene's
// intensities are meant for the other model.
void triangularLightHint(const SceneParameters& edits, const RenderSettings& settings) {
  if (edits.lights.of<TriangularLight>().empty()) return;
  float brightest = 0.0f;
  for (const TriangularLight& light : edits.lights.of<TriangularLight>())
    brightest = std::max({brightest, light.intensity.x, light.intensity.y, light.intensity.z});
  if (settings.triangularLightModel == TriangularLightModel::Area) {
    hintText("Area: each triangular light is N point lights spread over it (N = light samples; 1: its centroid), "
             "each I/N times the cosine at the light over d^2. Intensities as for point lights (hundreds, "
             "thousands).");
    return;
  }
  hintText("Directional: light arrives along the triangle's normal with intensity I and no 1/d^2 fall-off, like "
           "the sun. Expects I of about 0-255 per channel; light samples do not apply.");
  if (brightest > kDirectionalIntensityLimit) {
    char warning[256];
    std::snprintf(warning, sizeof warning,
                  "The triangular lights' intensities (up to %.0f) are meant for the area model: with no 1/d^2 "
                  "fall-off they are far too bright and the image goes white. Lower them in Lights, or use area.",
                  static_cast<double>(brightest));
    problemText(warning);
  }
}

// Exposure and gamma: display only, like the stats. The sliders change the texture, never the render.
void editDisplayMapping(DisplayMapping& mapping) {
  ImGui::SliderFloat("Exposure", &mapping.exposureStops, kMinExposureStops, kMaxExposureStops, "%+.1f stops",
                     ImGuiSliderFlags_AlwaysClamp);
  if (ImGui::IsItemHovered())
    tooltip("Display only, the render does not restart. Each value of the image times 2^stops: +1 doubles, "
                      "-1 halves; 0 shows the image as computed. The image holds 8-bit values, clamped to 255 by the "
                      "render: what it clipped to white stays one flat value. Ctrl+click to type a value.");
  ImGui::SliderFloat("Gamma", &mapping.gamma, kMinGamma, kMaxGamma, "%.2f",
                     ImGuiSliderFlags_AlwaysClamp | ImGuiSliderFlags_Logarithmic);
  if (ImGui::IsItemHovered())
    tooltip("Display only, the render does not restart. After the exposure, each value v (0 to 1) is shown "
                      "as v^(1/gamma): above 1 brightens the dark and middle tones, below 1 darkens them; black and "
                      "white stay. 1 shows the image as computed (the course applies no gamma).");
  ImGui::BeginDisabled(mapping.identity());
  if (ImGui::Button("Reset exposure and gamma")) mapping = DisplayMapping{};
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    tooltip("Exposure 0 and gamma 1: the image exactly as rayview render writes it.");
  hintText("The reference (Space) is shown with the same exposure and gamma; the difference view (D) is not.");
}

}  // namespace

std::string traversalBuilt(AccelKind chosen, AccelKind built, std::size_t triangles) {
  if (chosen == built) return {};
  const std::string name = chosen == AccelKind::Embree ? "Embree" : std::string(toString(chosen));
  if (chosen == AccelKind::Embree && built == AccelKind::Packet)
    return name + (triangles <= kSmallSceneTriangles ? " (packet BVH for small scenes)"
                                                     : " (packet BVH: Embree could not be loaded)");
  return name + " (" + std::string(toString(built)) + " built)";
}

void drawRenderSettingsPanel(SceneSession& session, DisplayOptions& display) {
  if (!ImGui::CollapsingHeader("Render", ImGuiTreeNodeFlags_DefaultOpen)) return;
  ImGui::Checkbox("Stats over the image", &display.showStats);  // display only: never restarts the render
  ImGui::SameLine();
  ImGui::Checkbox("On one line", &display.oneLineStats);
  if (ImGui::IsItemHovered())
    tooltip("The stats on one line. In a window smaller than 1280x800 they always are.");
  // The view (V): which pixels are rendered. Not a render setting of the scene: it is not in the knob table.
  const Camera& file = session.committedEdits().camera;
  if (ImGui::RadioButton("Window view", !display.imageView)) display.imageView = false;
  if (ImGui::IsItemHovered())
    tooltip("Renders the image area's own pixels: the file's view, with the near plane extended to the "
                      "area's shape (never cropped). Ctrl+S still saves the file's image. V switches.");
  ImGui::SameLine();
  const std::string imageLabel = "Image view (" + std::to_string(file.width) + "x" + std::to_string(file.height) + ")";
  if (ImGui::RadioButton(imageLabel.c_str(), display.imageView)) display.imageView = true;
  if (ImGui::IsItemHovered())
    tooltip("Renders the file's image, its resolution exactly: fit (0), 1:1 (1), zoom (+, -, Ctrl+wheel), "
                      "pan (Ctrl+drag). V switches.");
  editDisplayMapping(display.mapping);
  ImGui::Checkbox("Lights and pivot always", &display.alwaysShowMarks);
  if (ImGui::IsItemHovered())
    tooltip("Draw the lights (yellow) and the orbit pivot (white cross) over the image all the time. Off: only while "
            "you orbit, pan or dolly.");
  ImGui::Separator();
  // Every render knob, as the knob table describes it; then what the scene file says that is not a knob.
  for (const Knob& knob : knobTable()) {
    // The traversal as built for the scene on screen, while the choice is the one it was built for.
    std::string built;
    if (knob.name == "accel" && !session.needsRebuild())
      built = traversalBuilt(session.settings().accel, session.geometry().accel->kind(), session.loaded().triangles.size());
    editKnob(knob, session.edits(), session.settings(), built.empty() ? nullptr : built.c_str());
    if (knob.name == "tri-light") triangularLightHint(session.edits(), session.settings());
  }
  editRadiance("Background", session.edits().background);
}

StatsText statsText(const ViewerStats& s) {
  char level[64];
  if (s.stride <= 0) std::snprintf(level, sizeof level, "-");
  else if (s.stride == 1 && s.samples.total > 1)
    std::snprintf(level, sizeof level, "full resolution, %d/%d samples%s", s.samples.done, s.samples.total,
                  s.final ? " (final)" : "");
  else if (s.stride == 1) std::snprintf(level, sizeof level, "full resolution%s", s.final ? " (final)" : "");
  else std::snprintf(level, sizeof level, "1/%d (blocks of %dx%d)", s.stride, s.stride, s.stride);
  StatsText text;
  text.lines = {
      {"Preview level", level},
      {"Pass time", formatted("%.1f ms", s.passMs)},
      {"Speed", formatted("%.2f Mrays/s", s.megaRaysPerSecond)},
      {"Edit to first pass", millisecondsOrPending(s.editToFirstPassMs)},
      {"Edit to final pass", millisecondsOrPending(s.editToFinalPassMs)},
      {"Image", std::to_string(s.width) + " x " + std::to_string(s.height) +
                    (s.windowView ? " (window; file " + std::to_string(s.fileWidth) + " x " +
                                        std::to_string(s.fileHeight) + ")"
                                  : "")},
      {"Triangles", std::to_string(s.triangles)},
      {"Read", formatted("%.1f ms", s.readMs)},
      {"BVH build", formatted("%.1f ms", s.bvhBuildMs)},
      {"Traversal", s.traversal.empty() ? std::string(toString(s.accel)) : s.traversal},
      {"Threads", std::to_string(s.threads) + (s.tracedBy.empty() ? "" : " on rank 0; " + s.tracedBy)},
      {"Memory", memoryText(s.residentBytes, s.peakResidentBytes)},
      {"Generation", std::to_string(s.generation)},
  };
  // Single spaces about the bars: at 1000x640 the line then fits the image area without wrapping.
  text.oneLine = std::string(level) + " | " + text.lines[1].second + " | " + text.lines[2].second +
                 " | edit to final " + text.lines[4].second;
  if (!s.lostRanks.empty()) {
    std::string lost;
    for (const std::string& rank : s.lostRanks) lost += (lost.empty() ? "" : "; ") + rank;
    text.lines.push_back({"Lost", lost});
    text.oneLine += " | " + std::to_string(s.lostRanks.size()) + (s.lostRanks.size() == 1 ? " rank lost" : " ranks lost");
  }
  return text;
}

OverlaySize statsBoxSize(const StatsText& text) {
  const ImGuiStyle& style = ImGui::GetStyle();
  float nameWidth = 0.0f, valueWidth = 0.0f;
  for (const auto& [name, value] : text.lines) {
    nameWidth = std::max(nameWidth, ImGui::CalcTextSize(name.c_str()).x);
    valueWidth = std::max(valueWidth, ImGui::CalcTextSize(value.c_str()).x);
  }
  const float gap = 2.0f * style.ItemSpacing.x;
  return {nameWidth + gap + valueWidth + 2.0f * style.WindowPadding.x,
          text.lines.size() * ImGui::GetTextLineHeightWithSpacing() - style.ItemSpacing.y + 2.0f * style.WindowPadding.y,
          ImGui::GetTextLineHeightWithSpacing()};
}

void drawStatsOverlay(const StatsText& text, const OverlayRect& at, bool oneLine) {
  if (oneLine) return drawTextOverlay("##stats", text.oneLine, at, 0.65f);
  const ImGuiStyle& style = ImGui::GetStyle();
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoSavedSettings |
                                 ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav |
                                 ImGuiWindowFlags_NoInputs;
  // Sized from this frame's text: auto-resizing would lag a frame, and an idle viewer draws few frames.
  float nameWidth = 0.0f;
  for (const auto& line : text.lines) nameWidth = std::max(nameWidth, ImGui::CalcTextSize(line.first.c_str()).x);
  const float gap = 2.0f * style.ItemSpacing.x;
  ImGui::SetNextWindowPos(ImVec2(at.x, at.y));
  ImGui::SetNextWindowSize(ImVec2(at.width, at.height));
  ImGui::SetNextWindowBgAlpha(0.65f);
  if (ImGui::Begin("##stats", nullptr, flags)) {
    for (const auto& [name, value] : text.lines) {
      ImGui::TextUnformatted(name.c_str());
      ImGui::SameLine(style.WindowPadding.x + nameWidth + gap);
      ImGui::TextUnformatted(value.c_str());
    }
  }
  ImGui::End();
}

}  // namespace rayview
