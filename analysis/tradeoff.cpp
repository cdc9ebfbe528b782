#include "rayview/tradeoff.h"

#include "rayview/image_limits.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <thread>

#include "rayview/prepared_scene.h"
#include "rayview/knobs.h"
#include "rayview/tracer.h"
#include "tradeoff_timing.h"

namespace rayview {
namespace {

// ---- Enumeration

std::vector<int> depthsToList(int maxDepth, bool hasMirrors) {
  if (maxDepth <= 0) return {0};
  if (!hasMirrors) return {0, maxDepth};
  std::vector<int> depths;
  if (maxDepth <= kMaxDepthsListed) {
    for (int d = 0; d <= maxDepth; ++d) depths.push_back(d);
    return depths;
  }
  depths.push_back(0);
  for (int d = 1; d < maxDepth; d *= 2) depths.push_back(d);
  depths.push_back(maxDepth);
  return depths;
}

// 1, 2, 4 .. most, and `current` (the user's value) in its place when it is not one of them.
std::vector<int> doublingsWith(int most, int current) {
  std::vector<int> values;
  for (int n = 1;; n = std::min(2 * n, most)) {
    values.push_back(n);
    if (n == most) break;
  }
  if (std::find(values.begin(), values.end(), current) == values.end())
    values.insert(std::upper_bound(values.begin(), values.end(), current), current);
  return values;
}

std::string previewLabel(int stride) { return stride == 1 ? "1" : "1/" + std::to_string(stride); }

// One distinct render: several knob settings may share it.
struct Render {
  int stride = 1;
  int depth = 0;
  RenderSettings settings;
  std::string description;  // of the first knob setting that needs it
  std::vector<double> timesMs;
  ImageError error;
  std::uint64_t rays = 0;
  std::shared_ptr<const SceneParameters> view;  // what the tracer renders: the resized camera, this depth
  std::unique_ptr<const Tracer> tracer;
  bool quick = false;  // its first render took less than kMinTimedMs: timed in turn with the other quick ones
};

bool buildCancelled(void* user, double) { return !static_cast<const std::atomic<bool>*>(user)->load(); }

std::string formatNumber(const char* format, double value) {
  char text[64];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

std::string csvField(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

}  // namespace

const Knob* TradeoffKnob::row() const { return kind == Kind::Table ? findKnob(name) : nullptr; }

std::string toString(TradeoffKnob knob) {
  if (const Knob* row = knob.row()) return row->csvName();
  return knob.kind == TradeoffKnob::Kind::Preview ? "preview" : "best_image";
}

std::vector<TradeoffKnob> tradeoffKnobs() {
  std::vector<TradeoffKnob> knobs = {TradeoffKnob::Preview};
  for (const Knob& k : knobTable())
    if (k.measuredByTradeoff()) knobs.push_back(TradeoffKnob::of(k));
  return knobs;
}

KnobSweep TradeoffOptions::sweepOf(const Knob& knob) const {
  KnobSweep sweep = knob.tradeoff;
  for (const SweepLimit& l : limits)
    if (l.knob == knob.name) {
      sweep.max = std::min(sweep.max, l.max);
      if (l.best >= 0) sweep.best = l.best;
    }
  return sweep;
}

namespace {

// The values a knob's sweep lists for this scene and baseline (KnobSweep); empty when it changes nothing here.
std::vector<int> sweptValues(const Knob& knob, const KnobSweep& sweep, const SceneParameters& scene,
                             const RenderSettings& baseline) {
  switch (sweep.kind) {
    case TradeoffSweep::None: return {};
    case TradeoffSweep::UpToScene:
      return depthsToList(std::max(0, knob.get(scene, baseline)), !sweep.changesImage || sweep.changesImage(scene));
    case TradeoffSweep::Doublings:
      if (!knob.matters(scene, baseline)) return {};
      return doublingsWith(std::clamp(sweep.max, std::max(1, knob.min), std::max(1, knob.max)),
                           knob.get(scene, baseline));
    case TradeoffSweep::Values: return {sweep.values.begin(), sweep.values.end()};
  }
  return {};
}

// The best image improves what the user has where a row says how (more light samples, the reference BVH); it
// keeps the rest, the samples per pixel among them: anti-aliased images are not ranked against each other.
void improveForBestImage(const Knob& knob, const KnobSweep& sweep, SceneParameters& scene, RenderSettings& best) {
  if (sweep.best < 0 || !knob.matters(scene, best)) return;
  const int value = sweep.kind == TradeoffSweep::Doublings
                        ? std::clamp(std::max(sweep.best, knob.get(scene, best)), knob.min, knob.max)
                        : sweep.best;
  knob.set(scene, best, value);
}

// A setting of `knob` at `value` from the baseline; a Parameters knob the trade-off varies is the depth.
KnobSetting settingOf(TradeoffKnob id, const Knob& knob, int value, const SceneParameters& scene,
                      const RenderSettings& baseline) {
  SceneParameters parameters = scene;
  RenderSettings settings = baseline;
  knob.set(parameters, settings, value);
  return {id, knob.format(knob.get(parameters, settings)), 1, std::max(0, parameters.maxRayDepth), settings};
}

}  // namespace

std::vector<KnobSetting> enumerateKnobSettings(const SceneParameters& scene, const TradeoffOptions& options) {
  const int maxDepth = std::max(0, scene.maxRayDepth);
  RenderSettings baseline = options.baseline;
  baseline.accel = availableAccel(baseline.accel);

  SceneParameters bestScene = scene;
  bestScene.maxRayDepth = maxDepth;
  RenderSettings best = baseline;
  for (const Knob& k : knobTable())
    if (k.measuredByTradeoff()) improveForBestImage(k, options.sweepOf(k), bestScene, best);
  std::string bestLabel;  // "depth=6 light_samples=256 accel=reference samples=1", in the CSV's names
  for (const Knob& k : knobTable()) {
    if (!k.measuredByTradeoff()) continue;
    if (!bestLabel.empty()) bestLabel += ' ';
    bestLabel.append(k.csvName()).append("=").append(k.format(k.get(bestScene, best)));
  }
  std::vector<KnobSetting> list;
  list.push_back({TradeoffKnob::BestImage, bestLabel, 1, maxDepth, best});
  for (int stride : kPreviewStrides) list.push_back({TradeoffKnob::Preview, previewLabel(stride), stride, maxDepth, baseline});
  for (const Knob& k : knobTable())
    for (int value : sweptValues(k, options.sweepOf(k), scene, baseline))
      list.push_back(settingOf(TradeoffKnob::of(k), k, value, scene, baseline));
  return list;
}

std::string scaledImageProblem(const Camera& camera, double scale) {
  // The scaled camera meets the one image limit, as a scene's own resolution does: never 0 made 1, never more
  // pixels than the buffers can hold.
  const long long width = std::llround(camera.width * scale), height = std::llround(camera.height * scale);
  const std::string problem = imageSizeProblem(width, height);
  if (problem.empty()) return {};
  char factor[32];
  std::snprintf(factor, sizeof factor, "%g", scale);
  return "the resolution scale " + std::string(factor) + " makes the " + std::to_string(camera.width) + " x " +
         std::to_string(camera.height) + " image " + problem;
}

namespace {


// One measurement, as the stages it runs in order: plan the distinct renders, build the BVHs, make the tracers, run
// the rounds, report. A stage that returns false was cancelled.
class TradeoffRun {
 public:
  TradeoffRun(const SceneParameters& parameters, std::shared_ptr<const SceneGeometry> geometry,
              const std::string& sceneName, const TradeoffOptions& options, ThreadPool& pool,
              const std::atomic<bool>* cancel, const TradeoffProgressFn& progress);

  TradeoffReport run();

 private:
  void planRenders();
  bool buildGeometry();
  void makeTracers();
  bool runRound(int round);
  bool timeAlone(std::size_t i, int round, std::vector<std::size_t>& inTurn);
  bool timeQuickInTurn(const std::vector<std::size_t>& inTurn);
  void finish();
  int runsFor(const Render& r) const;
  bool cancelled() const { return cancel_ && cancel_->load(); }
  void tell(std::string what) {
    status_.what = std::move(what);
    if (progress_) progress_(status_);
  }
  TradeoffReport cancelledReport();

  const SceneParameters& parameters_;
  std::shared_ptr<const SceneGeometry> sceneGeometry_;
  const TradeoffOptions& options_;
  ThreadPool& pool_;
  const std::atomic<bool>* cancel_;
  const TradeoffProgressFn& progress_;
  const TimingClock::time_point start_ = TimingClock::now();
  TradeoffReport report_;
  SceneParameters view_;  // the parameters with the resized camera
  std::vector<KnobSetting> settings_;
  std::vector<Render> renders_;
  std::vector<std::size_t> renderOf_;  // the render of each setting
  std::shared_ptr<const PreparedGeometry> geometry_[kAccelKindCount];  // by AccelKind
  TradeoffProgress status_;
  Image bestImage_;
  int timedRuns_ = 1;
  int slowedRepeated_ = 0, slowedKept_ = 0;
};

TradeoffRun::TradeoffRun(const SceneParameters& parameters, std::shared_ptr<const SceneGeometry> geometry,
                         const std::string& sceneName, const TradeoffOptions& options, ThreadPool& pool,
                         const std::atomic<bool>* cancel, const TradeoffProgressFn& progress)
    : parameters_(parameters), sceneGeometry_(std::move(geometry)), options_(options), pool_(pool), cancel_(cancel),
      progress_(progress), view_(parameters), timedRuns_(std::max(1, options.timedRuns)) {
  report_.sceneName = sceneName;
  report_.threads = pool.size();
  // Camera, lights and materials from a resized copy; the meshes are read from the geometry.
  if (parameters.camera.width <= 0 || parameters.camera.height <= 0 || !(options.resolutionScale > 0.0))
    throw std::invalid_argument("the tradeoff needs a camera with pixels and a positive resolution scale");
  if (const std::string problem = scaledImageProblem(parameters.camera, options.resolutionScale); !problem.empty())
    throw std::invalid_argument(problem);
  view_.camera.width = report_.width = static_cast<int>(std::llround(parameters.camera.width * options.resolutionScale));
  view_.camera.height = report_.height = static_cast<int>(std::llround(parameters.camera.height * options.resolutionScale));
  if (!parameters.hasMirrors()) report_.notes.push_back("no mirrors (or depth 0): depth changes nothing");
  if (!lightSamplesKnob().matters(parameters, options.baseline))
    report_.notes.push_back("light samples change nothing here (no triangular lights, or the directional model): not measured");
  if (availableAccel(AccelKind::Embree) != AccelKind::Embree)
    report_.notes.push_back("built without Embree: rayview's packet BVH is measured in its place");
}

TradeoffReport TradeoffRun::run() {
  planRenders();
  if (!buildGeometry()) return cancelledReport();
  makeTracers();
  // Round 0 renders every setting and keeps its error (renders_[0] is the best image: it comes first); later
  // rounds only time. Interleaved rounds spread slow drifts of the machine's load over all settings.
  const int maxRuns = std::max(timedRuns_, options_.fastTimedRuns);
  for (int round = 0; round < maxRuns; ++round)
    if (!runRound(round)) return cancelledReport();
  finish();
  return std::move(report_);
}

// Settings that coincide (the baseline is the stride-1 preview, the depth's maximum, and one value of every other
// knob) share one render.
void TradeoffRun::planRenders() {
  settings_ = enumerateKnobSettings(parameters_, options_);
  const auto describe = [&](const KnobSetting& k) {
    SceneParameters rendered = view_;
    rendered.maxRayDepth = k.depth;
    return describeKnobs(rendered, k.settings);
  };
  for (const KnobSetting& k : settings_)
    if (k.knob == TradeoffKnob::Preview && k.stride == 1) report_.baseline = k;
  report_.baselineText = describe(report_.baseline);
  report_.bestText = describe(settings_.front());
  for (const KnobSetting& k : settings_) {
    const auto same = std::find_if(renders_.begin(), renders_.end(), [&](const Render& r) {
      return r.stride == k.stride && r.depth == k.depth && r.settings == k.settings;
    });
    renderOf_.push_back(static_cast<std::size_t>(same - renders_.begin()));
    if (same != renders_.end()) continue;
    Render& r = renders_.emplace_back();
    r.stride = k.stride;
    r.depth = k.depth;
    r.settings = k.settings;
    r.description = describeRow(k);
  }
  status_ = {0, static_cast<int>(renders_.size()) * timedRuns_, {}};
}

// Each accelerator the renders need, built once; not part of any time.
bool TradeoffRun::buildGeometry() {
  for (const Render& r : renders_) {
    auto& built = geometry_[static_cast<int>(r.settings.accel)];
    if (built) continue;
    if (cancelled()) return false;
    tell("building the " + std::string(toString(r.settings.accel)) + " BVH");
    built = prepareGeometry(sceneGeometry_, parameters_.camera.position, r.settings.accel, BvhBuild::Interactive,
                            cancel_ ? buildCancelled : nullptr, const_cast<std::atomic<bool>*>(cancel_), &parameters_);
    if (!built || cancelled()) return false;
    report_.buildMs[static_cast<int>(r.settings.accel)] = built->buildMs;
  }
  return true;
}

void TradeoffRun::makeTracers() {
  for (Render& r : renders_) {
    SceneParameters rendered = view_;
    rendered.maxRayDepth = r.depth;
    r.view = std::make_shared<const SceneParameters>(std::move(rendered));
    r.tracer = std::make_unique<const Tracer>(*r.view, *geometry_[static_cast<int>(r.settings.accel)], r.settings);
  }
}

int TradeoffRun::runsFor(const Render& r) const {
  const double first = r.timesMs.front();
  if (first > options_.singleRunMs) return 1;
  return first < options_.fastRunMs ? std::max(timedRuns_, options_.fastTimedRuns) : timedRuns_;
}

// In each round the quick renders are timed last, in turn with each other (tradeoff_timing.h).
bool TradeoffRun::runRound(int round) {
  std::vector<std::size_t> inTurn;
  for (std::size_t i = 0; i < renders_.size(); ++i) {
    Render& r = renders_[i];
    if (round > 0 && round >= runsFor(r)) continue;
    if (r.quick) {
      inTurn.push_back(i);
      continue;
    }
    if (!timeAlone(i, round, inTurn)) return false;
  }
  if (!inTurn.empty() && !timeQuickInTurn(inTurn)) return false;
  if (round == 0) {
    status_.rendersPlanned = 0;
    for (const Render& r : renders_) status_.rendersPlanned += runsFor(r);
  }
  return true;
}

// A run during which other processes held the cores is repeated (a few times at most): on a shared machine that
// keeps bursts of someone else's work out of the medians. Round 0 also keeps the image's error, and finds out
// whether the render is quick (then it is timed in turn with the others instead).
bool TradeoffRun::timeAlone(std::size_t i, int round, std::vector<std::size_t>& inTurn) {
  Render& r = renders_[i];
  if (cancelled()) return false;
  tell(r.description);
  TimedRun run;
  for (int attempt = 0;; ++attempt) {
    if (!renderOnce(*r.tracer, view_.camera.width, view_.camera.height, r.stride, pool_, cancel_, run)) return false;
    const bool slowed = run.wallMs >= kMinTimedMs && run.cpuShare < options_.minCpuShare;
    if (!slowed) break;
    if (attempt >= options_.slowedRetries) {
      ++slowedKept_;
      break;
    }
    ++slowedRepeated_;
    // Give a burst of someone else's work time to pass: 50 ms, 100 ms, 200 ms ...
    std::this_thread::sleep_for(std::chrono::milliseconds(50 << std::min(attempt, 5)));
    if (cancelled()) return false;
  }
  if (round == 0) {
    r.rays = run.rays.total();
    if (i == 0) bestImage_ = std::move(run.image);
    else r.error = compareToReference(run.image, bestImage_);
    r.quick = run.wallMs < kMinTimedMs;
    if (r.quick) {  // that render gave the image; the time comes in turn
      inTurn.push_back(i);
      return true;
    }
  }
  ++status_.rendersDone;
  r.timesMs.push_back(run.wallMs);
  return true;
}

bool TradeoffRun::timeQuickInTurn(const std::vector<std::size_t>& inTurn) {
  if (cancelled()) return false;
  tell(std::to_string(inTurn.size()) + " quick settings, in turn");
  std::vector<QuickRender> quick;
  for (std::size_t i : inTurn) quick.push_back({renders_[i].tracer.get(), renders_[i].stride, renders_[i].settings.accel});
  const std::vector<double> timesMs = timeInTurn(quick, view_.camera.width, view_.camera.height, pool_, cancel_);
  if (timesMs.empty()) return false;
  for (std::size_t k = 0; k < inTurn.size(); ++k) renders_[inTurn[k]].timesMs.push_back(timesMs[k]);
  status_.rendersDone += static_cast<int>(inTurn.size());
  return true;
}

void TradeoffRun::finish() {
  if (slowedRepeated_ > 0 || slowedKept_ > 0)
    report_.notes.push_back(std::to_string(slowedRepeated_) + " runs slowed by other processes were repeated" +
                            (slowedKept_ > 0 ? "; " + std::to_string(slowedKept_) + " kept (still slowed)" : ""));
  for (std::size_t k = 0; k < settings_.size(); ++k) {
    const Render& r = renders_[renderOf_[k]];
    report_.points.push_back({settings_[k], median(r.timesMs), static_cast<int>(r.timesMs.size()), r.error, r.rays});
  }
  report_.totalMs = msSince(start_);
}

TradeoffReport TradeoffRun::cancelledReport() {
  TradeoffReport r = std::move(report_);
  r.points.clear();
  r.cancelled = true;
  r.totalMs = msSince(start_);
  return r;
}

}  // namespace

TradeoffReport measureTradeoff(const SceneParameters& parameters, std::shared_ptr<const SceneGeometry> geometry,
                               const std::string& sceneName, const TradeoffOptions& options, ThreadPool& pool,
                               const std::atomic<bool>* cancel, const TradeoffProgressFn& progress) {
  return TradeoffRun(parameters, std::move(geometry), sceneName, options, pool, cancel, progress).run();
}

std::string tradeoffCsvHeader() { return "scene,knob,setting,time_ms,rmse,psnr_db,pct_off_by_more_than_1,rays\n"; }

std::string tradeoffCsvRows(const TradeoffReport& report) {
  std::string csv;
  for (const TradeoffPoint& p : report.points) {
    csv += csvField(report.sceneName) + "," + std::string(toString(p.setting.knob)) + "," +
           csvField(p.setting.label) + "," + formatNumber("%.3f", p.timeMs) + "," +
           formatNumber("%.4f", p.error.rmse) + "," +
           (std::isinf(p.error.psnrDb) ? std::string("inf") : formatNumber("%.2f", p.error.psnrDb)) + "," +
           formatNumber("%.4f", p.error.pctOffByMoreThan1) + "," + std::to_string(p.rays) + "\n";
  }
  return csv;
}

}  // namespace rayview
