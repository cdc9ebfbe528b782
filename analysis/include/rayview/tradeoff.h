#pragma once
// The speed-for-accuracy trade, measured so users can pick settings by cost and error. For each setting of each knob,
// varied alone from a baseline, render the scene, time it and compare it with the highest-quality image. No GL:
// `rayview bench tradeoff` and the viewer both use this.
//
// The knobs, each varied alone; the others stay at the baseline: full resolution, the depth of the parameters
// measured, and `options.baseline` (the viewer: the user's current settings and edits; the bench: the defaults
// and its options). Each knob's list includes the baseline's value:
// The knobs are the preview level and the knob table's rows that it marks as measured (Knob::tradeoff, which says
// how each is swept); today:
//   preview       pixel strides 16, 8, 4, 2, 1 (labelled 1/16 .. 1). The image is the blocky upscale the viewer
//                 shows (every pixel shows the sample at the top-left of its stride block); the time is that
//                 pass rendered alone from scratch, every pixel of its grid, not the incremental pass the
//                 progressive renderer runs after coarser ones.
//   depth         0 .. the scene's maximum (every value up to kMaxDepthsListed, then powers of two and the
//                 maximum). Without mirrors depth changes nothing: only 0 and the maximum are listed.
//   light_samples 1, 2, 4 .. maxLightSamples, area model; only when the scene has triangular lights.
//   accel         Embree (the packet BVH in its place when built without Embree) and the reference BVH.
//   samples       anti-aliasing, 1, 2, 4 .. maxPixelSamples camera rays per pixel. The best image keeps the
//                 baseline's count (1 by default, the course's convention): the error shown is how far
//                 anti-aliasing moves the image from it.
// The best image (the highest-quality one; the "best_image" row): the baseline with the reference BVH and at
// least referenceLightSamples (when light samples matter), at full resolution. It keeps the baseline's depth (the
// scene's own) and samples per pixel.
//
// Time: the median of `timedRuns` rounds (more for fast settings, one for very slow ones: see TradeoffOptions),
// on the same thread pool, interleaved round by round over all settings so that a change of machine load hits
// every setting alike. Only the render is timed (not the BVH build, reported once per accelerator, nor the
// upscale). In a round, a render of 20 ms or more is timed alone; a run that other processes slowed (its
// threads got well under their share of the CPU) is repeated, and the report's notes say how often that
// happened. Quicker renders (the coarse preview levels) are timed together at the end of the round, in turn,
// several times each, and each keeps its fastest time (the reasons: analysis/tradeoff_timing.h). Settings that
// coincide (the baseline is the stride-1 preview, the depth's maximum, and one value of every other knob) are
// rendered and timed once and share their figures.

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rayview/image_metrics.h"
#include "rayview/knobs.h"
#include "rayview/render_settings.h"
#include "rayview/scene.h"
#include "rayview/thread_pool.h"

namespace rayview {

// A row of the measurement: the best image (the highest-quality one every setting is compared with), the preview
// level, or a knob-table row the table marks as measured (Knob::tradeoff), named by the row's name. The best image is
// never called "reference": that word is the reference BVH's, a traversal back-end (the accel knob's choice).
struct TradeoffKnob {
  enum class Kind { BestImage, Preview, Table };
  Kind kind = Kind::BestImage;
  std::string_view name = {};  // the knob table's row, for Kind::Table

  constexpr bool operator==(const TradeoffKnob& other) const { return kind == other.kind && name == other.name; }
  // The knob-table row it varies; nullptr for the best image and the preview level.
  const Knob* row() const;
  static TradeoffKnob of(const Knob& knob) { return {Kind::Table, knob.name}; }

  static const TradeoffKnob BestImage, Preview, Depth, LightSamples, Accel, PixelSamples;
};
inline constexpr TradeoffKnob TradeoffKnob::BestImage{TradeoffKnob::Kind::BestImage};
inline constexpr TradeoffKnob TradeoffKnob::Preview{TradeoffKnob::Kind::Preview};
inline constexpr TradeoffKnob TradeoffKnob::Depth{TradeoffKnob::Kind::Table, "depth"};
inline constexpr TradeoffKnob TradeoffKnob::LightSamples{TradeoffKnob::Kind::Table, "light-samples"};
inline constexpr TradeoffKnob TradeoffKnob::Accel{TradeoffKnob::Kind::Table, "accel"};
inline constexpr TradeoffKnob TradeoffKnob::PixelSamples{TradeoffKnob::Kind::Table, "samples"};

// The CSV's and the bench's knob column: "best_image", "preview", and the knob table's CSV names ("depth",
// "light_samples", "accel", "samples").
std::string toString(TradeoffKnob knob);

inline constexpr int kPreviewStrides[] = {16, 8, 4, 2, 1};
inline constexpr int kMaxDepthsListed = 10;  // deeper scenes list 0, 1, 2, 4, 8 .. and their maximum

// A lower last value, or another best-image value, for a knob's sweep than its row gives (KnobSweep).
struct SweepLimit {
  std::string_view knob;  // the row's name
  int max = 0;
  int best = -1;          // -1: the row's
};

struct TradeoffOptions {
  double resolutionScale = 1.0;     // the camera resolution is multiplied by this (rounded, at least 1 pixel)
  std::vector<SweepLimit> limits;   // over the rows' own sweeps
  // What every setting starts from (its accel becomes the packet BVH when built without Embree).
  // Each knob row varies one of its fields; the knobs not measured here (the triangular-light model, the ray
  // start) are kept for every setting, the best image included.
  RenderSettings baseline;
  int timedRuns = 3;                // the time is the median of this many rounds, except:
  double singleRunMs = 10000.0;     //   a setting whose first run takes longer than this is run once,
  double fastRunMs = 250.0;         //   one whose first run takes less than this (noisier) ...
  int fastTimedRuns = 7;            //   ... this many times
  // A run of 20 ms or more whose threads got less than this share of the CPU time they could have used
  // (other processes held the cores) is repeated after a pause (50 ms, doubling), up to slowedRetries times,
  // then kept and counted in the notes.
  double minCpuShare = 0.8;
  int slowedRetries = 5;

  // Sweeps `knob` only up to `max` (Doublings) and gives the best image `best` of it (-1: the row's).
  void limit(const Knob& knob, int max, int best = -1) { limits.push_back({knob.name, max, best}); }
  // The row's sweep with the limits applied.
  KnobSweep sweepOf(const Knob& knob) const;
};

// One setting of one knob: what to render.
struct KnobSetting {
  TradeoffKnob knob = TradeoffKnob::BestImage;
  std::string label;        // the CSV's setting column: "1/16", "3", "64", "embree" (settingLabel: the panel's)
  int stride = 1;           // pixel stride of the grid rendered; 1 = every pixel
  int depth = 0;            // the max ray depth rendered (SceneParameters::maxRayDepth)
  RenderSettings settings;
};

// The words the viewer's panel and the plots use: "best image", "Preview level", and for the others the knob
// table's panel label ("Max ray depth", "Light samples", "Traversal", "Samples per pixel"), as the Render
// panel shows them; never the CSV's snake_case names.
inline constexpr std::string_view kBestImageLabel = "best image";
std::string_view knobLabel(TradeoffKnob knob);
// The knob-table row a knob of the measurement varies; nullptr for the best image and the preview level.
inline const Knob* tableKnob(TradeoffKnob knob) { return knob.row(); }
// The rows of the measurement: the preview level, then every measured row of the knob table, in its order.
std::vector<TradeoffKnob> tradeoffKnobs();
// The value the setting gives its knob-table row (tableKnob), as Knob::get reads it: the depth, a count, a
// choice's index. Nothing for the best image and the preview levels (not render settings).
std::optional<int> knobValue(const KnobSetting& setting);
// A setting in the panel's words: "1/16", "3", "Embree", "reference BVH"; "" for the best image.
std::string settingLabel(const KnobSetting& setting);
// "Light samples 4", "Preview level 1/16", "best image": the row, in the panel's words.
std::string describeRow(const KnobSetting& setting);

// The settings measured for `scene`, the best image first, then knob by knob in the order listed above.
std::vector<KnobSetting> enumerateKnobSettings(const SceneParameters& scene, const TradeoffOptions& options);

struct TradeoffPoint {
  KnobSetting setting;
  double timeMs = 0.0;       // median render time over the rounds
  int runs = 0;              // rounds the median was taken over
  ImageError error;          // against the best image
  std::uint64_t rays = 0;    // rays of one render
};

struct TradeoffReport {
  std::string sceneName;     // the file's stem ("default" for the embedded scene)
  int width = 0, height = 0; // the resolution rendered (after resolutionScale)
  int threads = 0;
  double buildMs[kAccelKindCount] = {};  // by AccelKind: each accelerator's build, 0 for one not built
  double totalMs = 0.0;      // the whole measurement, builds included
  KnobSetting baseline;      // what every knob was varied from (the stride-1 preview)
  std::string baselineText;  // describeKnobs of the baseline: "Max ray depth 3, Light samples 4, ..."
  std::string bestText;      // the same for the highest-quality image
  std::vector<TradeoffPoint> points;  // in enumerateKnobSettings order; the best image first
  std::vector<std::string> notes;     // what a reader should know ("no mirrors: depth changes nothing")
  bool cancelled = false;    // then `points` is empty
};

struct TradeoffProgress {
  int rendersDone = 0;
  int rendersPlanned = 0;    // exact once every setting has been rendered once (it depends on their times)
  std::string what;          // "Max ray depth 3", "building the reference BVH"
};
using TradeoffProgressFn = std::function<void(const TradeoffProgress&)>;

// Measures every setting of enumerateKnobSettings(*scene, options) on `pool`.
// - `parameters` are what is rendered (the viewer's current edits); `geometry` the scene's geometry. The BVHs are built here, once per accelerator, and are not part of any time.
// - Blocks the calling thread for as long as the renders take (seconds to minutes): the viewer calls it from a
//   worker thread of its own, never from the UI thread, and pauses its progressive renderer meanwhile, or the
//   times mean little.
// - Raising `*cancel` stops within one tile of rendering; the report then says cancelled.
// - `progress` is called on the calling thread before every BVH build, every render timed alone and every
//   round's quick renders timed in turn.
// Throws std::invalid_argument for a camera without pixels or a resolution scale <= 0, or a scaled image
// scaledImageProblem refuses.
TradeoffReport measureTradeoff(const SceneParameters& parameters, std::shared_ptr<const SceneGeometry> geometry,
                               const std::string& sceneName, const TradeoffOptions& options, ThreadPool& pool,
                               const std::atomic<bool>* cancel = nullptr, const TradeoffProgressFn& progress = {});

// Why `camera` at `scale` times its resolution cannot be measured ("" when it can): the scaled image meets the one
// image limit (rayview/image_limits.h), so neither 0 pixels nor more than its buffers hold. Callers check it before
// any work.
std::string scaledImageProblem(const Camera& camera, double scale);

// The CSV the bench writes: a header line, then one line per point of every report.
// Columns: scene, knob, setting, time_ms, rmse, psnr_db ("inf" when exact), pct_off_by_more_than_1, rays.
std::string tradeoffCsvHeader();
std::string tradeoffCsvRows(const TradeoffReport& report);

}  // namespace rayview
