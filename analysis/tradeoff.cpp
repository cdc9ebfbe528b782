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

std::string_view toString(TradeoffKnob knob) {
  static const std::string depthName = depthKnob().csvName(), samplesName = lightSamplesKnob().csvName(),
                           accelName = accelKnob().csvName(), pixelSamplesName = pixelSamplesKnob().csvName();
  switch (knob) {
    case TradeoffKnob::BestImage: return "best_image";
    case TradeoffKnob::Preview: return "preview";
    case TradeoffKnob::Depth: return depthName;
    case TradeoffKnob::LightSamples: return samplesName;
    case TradeoffKnob::Accel: return accelName;
    case TradeoffKnob::PixelSamples: return pixelSamplesName;
  }
  return "?";
}

std::vector<KnobSetting> enumerateKnobSettings(const SceneParameters& scene, const TradeoffOptions& options) {
  const int maxDepth = std::max(0, scene.maxRayDepth);
  RenderSettings baseline = options.baseline;
  baseline.accel = availableAccel(baseline.accel);
  const bool samplesMatter = lightSamplesKnob().matters(scene, baseline);

  std::vector<KnobSetting> list;
  // The best image improves what the user has: more light samples, the reference BVH. It keeps their samples
  // per pixel: anti-aliased images are not ranked against each other (docs/tradeoff.md).
  RenderSettings best = baseline;
  best.accel = availableAccel(AccelKind::Reference);
  if (samplesMatter)
    best.lightSamples = std::clamp(std::max(options.referenceLightSamples, baseline.lightSamples), 1, kMaxLightSamples);
  SceneParameters atDepth;
  atDepth.maxRayDepth = maxDepth;
  std::string bestLabel;  // "depth=6 light_samples=256 accel=reference samples=1", in the CSV's names
  for (const Knob* k : {&depthKnob(), &lightSamplesKnob(), &accelKnob(), &pixelSamplesKnob()}) {
    if (!bestLabel.empty()) bestLabel += ' ';
    bestLabel.append(k->csvName()).append("=").append(k->format(k->get(atDepth, best)));
  }
  list.push_back({TradeoffKnob::BestImage, bestLabel, 1, maxDepth, best});

  for (int stride : kPreviewStrides) list.push_back({TradeoffKnob::Preview, previewLabel(stride), stride, maxDepth, baseline});

  for (int depth : depthsToList(maxDepth, scene.hasMirrors())) {
    list.push_back({TradeoffKnob::Depth, std::to_string(depth), 1, depth, baseline});
  }

  if (samplesMatter) {
    for (int n : doublingsWith(std::clamp(options.maxLightSamples, 1, kMaxLightSamples), baseline.lightSamples)) {
      RenderSettings s = baseline;
      s.lightSamples = n;
      list.push_back({TradeoffKnob::LightSamples, std::to_string(n), 1, maxDepth, s});
    }
  }

  // The fast traversal this build has (Embree, or the packet BVH in its place) and the reference BVH.
  for (AccelKind kind : {availableAccel(AccelKind::Embree), AccelKind::Reference}) {
    RenderSettings s = baseline;
    s.accel = kind;
    list.push_back({TradeoffKnob::Accel, std::string(toString(kind)), 1, maxDepth, s});
  }

  for (int n : doublingsWith(std::clamp(options.maxPixelSamples, 1, kMaxPixelSamples), baseline.pixelSamples)) {
    RenderSettings s = baseline;
    s.pixelSamples = n;
    list.push_back({TradeoffKnob::PixelSamples, std::to_string(n), 1, maxDepth, s});
  }
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

TradeoffReport measureTradeoff(const SceneParameters& parameters, std::shared_ptr<const SceneGeometry> sceneGeometry,
                               const std::string& sceneName, const TradeoffOptions& options, ThreadPool& pool,
                               const std::atomic<bool>* cancel, const TradeoffProgressFn& progress) {
  const auto start = TimingClock::now();
  TradeoffReport report;
  report.sceneName = sceneName;
  report.threads = pool.size();

  // Camera, lights and materials from a resized copy; the meshes are read from the geometry.
  const SceneParameters* scene = &parameters;
  SceneParameters view = parameters;
  if (scene->camera.width <= 0 || scene->camera.height <= 0 || !(options.resolutionScale > 0.0))
    throw std::invalid_argument("the tradeoff needs a camera with pixels and a positive resolution scale");
  if (const std::string problem = scaledImageProblem(scene->camera, options.resolutionScale); !problem.empty())
    throw std::invalid_argument(problem);
  view.camera.width = report.width = static_cast<int>(std::llround(scene->camera.width * options.resolutionScale));
  view.camera.height = report.height = static_cast<int>(std::llround(scene->camera.height * options.resolutionScale));

  if (!scene->hasMirrors()) report.notes.push_back("no mirrors (or depth 0): depth changes nothing");
  if (!lightSamplesKnob().matters(*scene, options.baseline))
    report.notes.push_back("light samples change nothing here (no triangular lights, or the directional model): not measured");
  if (availableAccel(AccelKind::Embree) != AccelKind::Embree)
    report.notes.push_back("built without Embree: rayview's packet BVH is measured in its place");

  const std::vector<KnobSetting> settings = enumerateKnobSettings(*scene, options);
  const auto describe = [&](const KnobSetting& k) {
    SceneParameters rendered = view;
    rendered.maxRayDepth = k.depth;
    return describeKnobs(rendered, k.settings);
  };
  for (const KnobSetting& k : settings)
    if (k.knob == TradeoffKnob::Preview && k.stride == 1) report.baseline = k;
  report.baselineText = describe(report.baseline);
  report.bestText = describe(settings.front());
  std::vector<Render> renders;
  std::vector<std::size_t> renderOf;
  for (const KnobSetting& k : settings) {
    const auto same = std::find_if(renders.begin(), renders.end(),
                                   [&](const Render& r) {
                                     return r.stride == k.stride && r.depth == k.depth && r.settings == k.settings;
                                   });
    renderOf.push_back(static_cast<std::size_t>(same - renders.begin()));
    if (same == renders.end()) {
      Render& r = renders.emplace_back();
      r.stride = k.stride;
      r.depth = k.depth;
      r.settings = k.settings;
      r.description = describeRow(k);
    }
  }

  const auto isCancelled = [&] { return cancel && cancel->load(); };
  const auto cancelledReport = [&] {
    TradeoffReport r = std::move(report);
    r.points.clear();
    r.cancelled = true;
    r.totalMs = msSince(start);
    return r;
  };
  const int timedRuns = std::max(1, options.timedRuns);
  TradeoffProgress status{0, static_cast<int>(renders.size()) * timedRuns, {}};
  const auto tell = [&](std::string what) {
    status.what = std::move(what);
    if (progress) progress(status);
  };

  std::shared_ptr<const PreparedGeometry> geometry[kAccelKindCount];  // by AccelKind
  for (const Render& r : renders) {
    auto& built = geometry[static_cast<int>(r.settings.accel)];
    if (built) continue;
    if (isCancelled()) return cancelledReport();
    tell("building the " + std::string(toString(r.settings.accel)) + " BVH");
    built = prepareGeometry(sceneGeometry, parameters.camera.position, r.settings.accel, cancel ? buildCancelled : nullptr,
                            const_cast<std::atomic<bool>*>(cancel));
    if (!built || isCancelled()) return cancelledReport();
    report.buildMs[static_cast<int>(r.settings.accel)] = built->buildMs;
  }

  for (Render& r : renders) {
    SceneParameters rendered = view;
    rendered.maxRayDepth = r.depth;
    r.view = std::make_shared<const SceneParameters>(std::move(rendered));
    r.tracer = std::make_unique<const Tracer>(*r.view, *geometry[static_cast<int>(r.settings.accel)], r.settings);
  }

  // Round 0 renders every setting and keeps its error (renders[0] is the best image: it comes first); later
  // rounds only time. Interleaved rounds spread slow drifts of the machine's load over all settings. In each
  // round the quick renders are timed last, in turn with each other (tradeoff_timing.h).
  const auto runsFor = [&](const Render& r) {
    const double first = r.timesMs.front();
    if (first > options.singleRunMs) return 1;
    return first < options.fastRunMs ? std::max(timedRuns, options.fastTimedRuns) : timedRuns;
  };
  const int maxRuns = std::max(timedRuns, options.fastTimedRuns);
  const int width = view.camera.width, height = view.camera.height;
  Image bestImage;
  int slowedRepeated = 0, slowedKept = 0;
  for (int round = 0; round < maxRuns; ++round) {
    std::vector<std::size_t> inTurn;
    for (std::size_t i = 0; i < renders.size(); ++i) {
      Render& r = renders[i];
      if (round > 0 && round >= runsFor(r)) continue;
      if (r.quick) {
        inTurn.push_back(i);
        continue;
      }
      if (isCancelled()) return cancelledReport();
      tell(r.description);
      TimedRun run;
      // A run during which other processes held the cores is repeated (a few times at most): on a shared
      // machine that keeps bursts of someone else's work out of the medians.
      for (int attempt = 0;; ++attempt) {
        if (!renderOnce(*r.tracer, width, height, r.stride, pool, cancel, run)) return cancelledReport();
        const bool slowed = run.wallMs >= kMinTimedMs && run.cpuShare < options.minCpuShare;
        if (!slowed) break;
        if (attempt >= options.slowedRetries) {
          ++slowedKept;
          break;
        }
        ++slowedRepeated;
        // Give a burst of someone else's work time to pass: 50 ms, 100 ms, 200 ms ...
        std::this_thread::sleep_for(std::chrono::milliseconds(50 << std::min(attempt, 5)));
        if (isCancelled()) return cancelledReport();
      }
      if (round == 0) {
        r.rays = run.rays.total();
        if (i == 0) bestImage = std::move(run.image);
        else r.error = compareToReference(run.image, bestImage);
        r.quick = run.wallMs < kMinTimedMs;
        if (r.quick) {  // that render gave the image; the time comes below
          inTurn.push_back(i);
          continue;
        }
      }
      ++status.rendersDone;
      r.timesMs.push_back(run.wallMs);
    }
    if (!inTurn.empty()) {
      if (isCancelled()) return cancelledReport();
      tell(std::to_string(inTurn.size()) + " quick settings, in turn");
      std::vector<QuickRender> quick;
      for (std::size_t i : inTurn) quick.push_back({renders[i].tracer.get(), renders[i].stride, renders[i].settings.accel});
      const std::vector<double> timesMs = timeInTurn(quick, width, height, pool, cancel);
      if (timesMs.empty()) return cancelledReport();
      for (std::size_t k = 0; k < inTurn.size(); ++k) renders[inTurn[k]].timesMs.push_back(timesMs[k]);
      status.rendersDone += static_cast<int>(inTurn.size());
    }
    if (round == 0) {
      status.rendersPlanned = 0;
      for (const Render& r : renders) status.rendersPlanned += runsFor(r);
    }
  }

  if (slowedRepeated > 0 || slowedKept > 0)
    report.notes.push_back(std::to_string(slowedRepeated) + " runs slowed by other processes were repeated" +
                           (slowedKept > 0 ? "; " + std::to_string(slowedKept) + " kept (still slowed)" : ""));

  for (std::size_t k = 0; k < settings.size(); ++k) {
    const Render& r = renders[renderOf[k]];
    report.points.push_back({settings[k], median(r.timesMs), static_cast<int>(r.timesMs.size()), r.error, r.rays});
  }
  report.totalMs = msSince(start);
  return report;
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
