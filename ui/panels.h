#pragma once
// The viewer's ImGui panels. Each draws one concern and edits only what it is given; requests that
// need the application (open, save, reload) come back as PanelActions.

#include <array>
#include <cstdint>
#include <utility>
#include <optional>
#include <string>
#include <vector>

#include "display_mapping.h"
#include "image_texture.h"
#include "overlay_layout.h"
#include "rayview/model_options.h"
#include "rayview/diagnostics.h"
#include "rayview/progressive_renderer.h"
#include "rayview/tradeoff.h"
#include "recent_files.h"
#include "reference_compare.h"
#include "scene_loader_task.h"
#include "scene_session.h"

namespace rayview {

struct PanelActions {
  std::optional<std::string> open;
  bool reload = false;
  bool saveFrame = false;
  bool saveView = false;  // the image area as seen, read back from the window
  bool saveSceneNumbered = false;
  std::optional<std::string> saveSceneAs;
  bool frameScene = false;
  bool resetCamera = false;
  bool togglePanels = false;
  std::optional<double> measureTradeoff;  // at this resolution scale
  bool cancelTradeoff = false;
  std::optional<std::string> loadReference;  // the Compare panel's path
  bool toggleDifference = false;
  std::optional<std::size_t> applyTradeoffRow;  // Apply: the row's setting (an index into the report's points)
  std::optional<ModelUpAxis> modelUp;  // the Scene panel's Up axis: read the model again with it
};

// The text fields and toggles of the file panels, kept between frames.
struct FilePanelState {
  std::string openPath;
  std::string saveScenePath;
  std::string lastSaved;  // "saved /path/scene_001.png", shown under the buttons
  bool lastSaveFailed = false;  // lastSaved is an error: shown in red, whole, wrapped
  bool frameSavePending = false;  // Ctrl+S waits for the final pass
  // Save frame and Ctrl+S write the image as displayed (exposure and gamma applied) rather than raw, the default:
  // raw is what `rayview render` writes.
  bool saveFrameDisplayed = false;
  bool reloadOnChange = true;
  // Ctrl+O: open the Scene section, focus the path field with its text selected. ImGui activates the field a
  // frame or two after the request; characters typed meanwhile are held here and replayed into the field.
  bool focusOpenPath = false;   // requested, the field is not active yet
  int focusFrames = 0;          // frames since the request (the focus is requested again after a few)
  std::vector<unsigned int> typeAhead;
  bool enterAhead = false;  // Enter was pressed meanwhile: open once the held characters are in the field
};

// Display only: none of these restarts the render.
struct DisplayOptions {
  bool showStats = true;
  bool oneLineStats = false;  // the stats on one line even in a large window (a small one always has them so)
  bool hidePanels = false;    // F9: the image takes the whole window
  // V: the image view (the file's image: fit, 1:1, zoom) instead of the window view (the image area's own
  // pixels, the file's view extended to its aspect; rayview/view_camera.h).
  bool imageView = false;
  DisplayMapping mapping;     // exposure and gamma of the render and the reference (the difference stays raw)
  bool alwaysShowMarks = false;  // the lights and the orbit pivot drawn in the view always, not only while navigating
  bool showHelp = false;         // F1 or ?: the keys and mouse gestures over the image
};

// Below this window size (at content scale 1) the stats take one line, so they do not cover the image.
inline constexpr float kCompactStatsWidth = 1280.0f;
inline constexpr float kCompactStatsHeight = 800.0f;

// The resolution scales the "Speed vs accuracy" panel offers (of the camera's image); the first is the default.
inline constexpr double kTradeoffScales[] = {0.25, 0.5, 1.0};

// The "Speed vs accuracy" panel: the choice, the measurement in progress and the last result.
struct TradeoffPanelState {
  int scaleIndex = 0;  // into kTradeoffScales
  bool running = false;
  TradeoffProgress progress;
  double fraction = 0.0;
  std::string message;                   // why the last measurement has no result ("cancelled: ...")
  std::optional<TradeoffReport> report;  // the last finished measurement (its plot is the texture)
  bool stale = false;                    // the scene was edited or replaced since
  bool reveal = false;                   // open the header and scroll to it once (a new result)
  bool showPlot = false;                 // the plot floats over the image (turned on by a new result)
};

// The "Compare" panel: the reference's path field and the difference view (its checkbox and D).
struct ComparePanelState {
  std::string path;
  bool filledBeside = false;  // `path` is SCENE.png found beside the scene, filled in for the user
  bool showDifference = false;
  bool reveal = false;  // open the header and scroll to it once (a reference was given or loaded)
};

// What the Compare panel shows of the comparison: the reference, the image on screen and its figures.
struct CompareInfo {
  const ReferenceComparison& comparison;
  int imageWidth = 0, imageHeight = 0;  // of the image on screen; 0 before the first pass
  bool figuresCurrent = false;          // the figures are of the final pass on screen (not refining)
  std::string cameraMismatch;           // why the camera on screen is not the reference's ("" when it is)
};

struct CameraPanelState {
  bool keepFieldOfView = true;  // a resolution edit changes the other side, not the near plane
  std::string resolutionProblem;  // why the last resolution entered was not applied ("" when it was)
};

// Why a resolution typed into the Camera panel is refused ("" when it is taken): a side below 1.
std::string resolutionRefusal(int width, int height);

// What the stats panel shows, gathered by the application from the renderer and the loader.
struct ViewerStats {
  int stride = 0;                 // of the frame on screen; 1 = full resolution
  SampleCount samples;            // anti-aliasing samples per pixel in the frame on screen, of the setting's
  bool final = false;
  double passMs = 0.0;
  double megaRaysPerSecond = 0.0;
  double editToFirstPassMs = -1.0;  // -1: not yet
  double editToFinalPassMs = -1.0;
  std::uint64_t generation = 0;
  int width = 0, height = 0;
  bool windowView = false;             // the image is the window view's, not the file's
  int fileWidth = 0, fileHeight = 0;   // the file's resolution (what Ctrl+S saves)
  std::size_t triangles = 0;
  double readMs = 0.0;
  double bvhBuildMs = 0.0;
  AccelKind accel = AccelKind::Embree;  // the back-end built for the scene (the packet BVH for a small one)
  std::string traversal;                // how the stats name it ("" = toString(accel))
  int threads = 0;
  std::string tracedBy;  // the other processes tracing the passes (rayview/pass_farm.h); "" when none
  std::vector<std::string> lostRanks;  // of those, the ones that died or were left out, each with why
  // The process's resident memory and its peak, in bytes, read at each pass shown (0: not known).
  std::uint64_t residentBytes = 0, peakResidentBytes = 0;
};

struct SceneInfo {
  std::string displayName;  // the path, or "default scene (embedded)"
  const std::vector<Diagnostic>& warnings;
  std::optional<ModelUpAxis> modelUp;  // a model on screen: which of its axes points up
};

// A scene with thousands of repaired lines lists this many; the rest are counted.
inline constexpr std::size_t kMaxListedWarnings = 200;

// The panel column on the left of the window.
void drawScenePanel(FilePanelState& state, const RecentFiles& recent, const SceneInfo& info, const LoadProgress& progress,
                    PanelActions& actions);
void drawSavePanel(FilePanelState& state, bool haveFrame, PanelActions& actions);
void drawCameraPanel(SceneSession& session, CameraPanelState& state, const std::string& problem, PanelActions& actions);
void drawLightsPanel(SceneParameters& edits, double sceneRadius);
// `picked`: the material of the picked mesh, marked; `reveal`: open it (and the section) and scroll to it, once.
void drawMaterialsPanel(SceneParameters& edits, bool hasTexture, std::optional<std::size_t> picked, bool reveal);
void drawRenderSettingsPanel(SceneSession& session, DisplayOptions& display);
// `canMeasure` is false (with `why`) while no scene can be measured. `edits` and `settings` are the user's
// now: the row matching them has no Apply button.
void drawTradeoffPanel(TradeoffPanelState& state, const SceneParameters& edits, const RenderSettings& settings,
                       bool canMeasure, const std::string& why, PanelActions& actions);

void drawComparePanel(ComparePanelState& state, const CompareInfo& info, PanelActions& actions);

// The stats over the image: preview level, pass time, Mrays/s, latencies, sizes; as a box of named lines, or the
// level, pass time, speed and the edit's latency on one line.
struct StatsText {
  std::vector<std::pair<std::string, std::string>> lines;  // name, value
  std::string oneLine;
};
StatsText statsText(const ViewerStats& stats);
// The traversal a scene is rendered with, as the Render panel's dropdown and the stats both name it: the chosen
// one, or what was built for it when that differs ("Embree (packet BVH for small scenes)"); "" when they agree.
std::string traversalBuilt(AccelKind chosen, AccelKind built, std::size_t triangles);
// Up to this many triangles a scene asked for Embree gets rayview's packet BVH (the accel knob's help says so).
inline constexpr std::size_t kSmallSceneTriangles = 5000;
OverlaySize statsBoxSize(const StatsText& text);
// At `at` (placed by placeOverlays): the box, or the line wrapped to the rectangle's width.
void drawStatsOverlay(const StatsText& text, const OverlayRect& at, bool oneLine);

// A text over the image: its size on one line (plus what each wrapped line adds), and drawn at `at`, wrapped to
// its width. `background`: the window's colour (alpha 1), else the style's at `alpha`.
OverlaySize textOverlaySize(const std::string& text);
void drawTextOverlay(const char* id, const std::string& text, const OverlayRect& at, float alpha,
                     std::optional<std::array<float, 3>> background = std::nullopt);

// Floating over the top of the image, one under the other: the located load error (with a dismiss button)
// and the load progress. Each returns the y below itself (`y` when it is not shown).
float drawErrorOverlay(std::string& error, const std::string& stillShowing, float x, float y, float width);
// F1 or ?: the shortcut table over the image area (x, y, width, height); its close button clears `open`.
void drawHelpOverlay(bool& open, float x, float y, float width, float height);
float drawLoadingOverlay(const LoadProgress& progress, float x, float y, float width);
// The plot of the last measurement (the texture), at its size or smaller to fit, closable (state.showPlot).
void drawTradeoffPlot(TradeoffPanelState& state, const ImageTexture& plot, float x, float y, float maxWidth,
                      float maxHeight);

}  // namespace rayview
