#include "bench_command.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>
#include <string>

#include "rayview/plot.h"
#include "rayview/tradeoff.h"
#include "rayview/scene_open.h"

namespace rayview {
namespace {

// File stems, made unique ("scene2", "scene2_2") so two scenes never share a plot.
std::vector<std::string> uniqueNames(const std::vector<std::string>& paths) {
  std::vector<std::string> names;
  std::set<std::string> taken;
  for (const std::string& path : paths) {
    const std::string stem = std::filesystem::path(path).stem().string();
    std::string name = stem;
    for (int n = 2; taken.count(name); ++n) name = stem + "_" + std::to_string(n);
    taken.insert(name);
    names.push_back(name);
  }
  return names;
}

void printTable(const TradeoffReport& report) {
  std::string builds;
  for (int kind = 0; kind < kAccelKindCount; ++kind) {
    if (report.buildMs[kind] <= 0.0) continue;
    char text[64];
    std::snprintf(text, sizeof text, "%s%s %.1f ms", builds.empty() ? "" : ", ",
                  std::string(toString(static_cast<AccelKind>(kind))).c_str(), report.buildMs[kind]);
    builds += text;
  }
  std::printf("%s: %dx%d, %d threads, measured in %.1f s (BVH build: %s)\n", report.sceneName.c_str(), report.width,
              report.height, report.threads, report.totalMs / 1000.0, builds.c_str());
  std::printf("  best image: %s\n  baseline: %s\n", report.bestText.c_str(), report.baselineText.c_str());
  for (const std::string& note : report.notes) std::printf("  note: %s\n", note.c_str());
  const double bestMs = report.points.empty() ? 0.0 : report.points.front().timeMs;
  int settingWidth = 8;  // the best image's setting ("depth=6 light_samples=256 ...") is the widest
  for (const TradeoffPoint& p : report.points) settingWidth = std::max(settingWidth, static_cast<int>(p.setting.label.size()));
  std::printf("  %-13s %-*s %10s %8s %9s %8s %8s %12s\n", "knob", settingWidth, "setting", "time ms", "x best", "rmse",
              "psnr dB", "% off>1", "rays");
  for (const TradeoffPoint& p : report.points) {
    char psnr[16];
    if (std::isinf(p.error.psnrDb)) std::snprintf(psnr, sizeof psnr, "inf");
    else std::snprintf(psnr, sizeof psnr, "%.2f", p.error.psnrDb);
    std::printf("  %-13s %-*s %10.2f %8.2f %9.4f %8s %8.3f %12llu\n", std::string(toString(p.setting.knob)).c_str(),
                settingWidth, p.setting.label.c_str(), p.timeMs, p.timeMs > 0.0 ? bestMs / p.timeMs : 0.0, p.error.rmse, psnr,
                p.error.pctOffByMoreThan1, static_cast<unsigned long long>(p.rays));
  }
}

}  // namespace

int runBenchCommand(const CommandLine& command) {
  // Every scene is read before anything is measured or written: a bad scene costs nothing.
  std::vector<std::shared_ptr<const Scene>> scenes;
  for (const std::string& path : command.job.scenes) {
    try {
      LoadedScene loaded = openScene(path, command.job.open, nullptr, command.job.threads);
      if (!command.job.quiet)
        for (const Diagnostic& warning : loaded.warnings) std::fprintf(stderr, "%s\n", warning.format().c_str());
      if (const std::string problem = scaledImageProblem(loaded.scene.camera, command.resolutionScale); !problem.empty()) {
        std::fprintf(stderr, "%s: error: %s\n", path.empty() ? "default scene" : path.c_str(), problem.c_str());
        return kExitBadInput;
      }
      scenes.push_back(std::make_shared<const Scene>(std::move(loaded.scene)));
    } catch (const SceneError& error) {
      std::fprintf(stderr, "%s\n", error.what());
      return kExitBadInput;
    }
  }

  const std::filesystem::path directory = command.outputDirectory;
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error) {
    std::fprintf(stderr, "rayview: error: cannot create %s: %s\n", directory.c_str(), error.message().c_str());
    return kExitIoFailure;
  }

  ThreadPool pool(command.job.threads);
  TradeoffOptions options;
  options.resolutionScale = command.resolutionScale;
  options.baseline = renderSettingsOf(command.job);
  const bool showProgress = !command.job.quiet && isatty(fileno(stderr));
  const std::vector<std::string> names = uniqueNames(command.job.scenes);
  std::string csv = tradeoffCsvHeader();
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    const TradeoffProgressFn progress = [&](const TradeoffProgress& p) {
      std::fprintf(stderr, "\r\033[K%s: [%d/%d] %s", names[i].c_str(), p.rendersDone, p.rendersPlanned, p.what.c_str());
    };
    const std::shared_ptr<const Scene>& scene = scenes[i];
    TradeoffReport report = measureTradeoff(*scene, std::shared_ptr<const SceneGeometry>(scene, &scene->geometry()),
                                            names[i], options, pool, nullptr, showProgress ? progress : nullptr);
    if (showProgress) std::fputs("\r\033[K", stderr);
    report.sceneName = names[i];
    csv += tradeoffCsvRows(report);
    const std::filesystem::path plotPath = directory / (names[i] + "_tradeoff.png");
    try {
      // The CSV is rewritten after every scene, so a long run keeps what it has measured.
      writeFileAtomically(directory / "tradeoff.csv", csv);
      writeImageFile(plotPath, plotTradeoff(report));
    } catch (const ImageIoError& e) {
      std::fprintf(stderr, "rayview: error: %s\n", e.what());
      return kExitIoFailure;
    }
    if (!command.job.quiet) {
      printTable(report);
      std::printf("  wrote %s\n\n", std::filesystem::absolute(plotPath).c_str());
    }
  }
  if (!command.job.quiet) std::printf("wrote %s\n", std::filesystem::absolute(directory / "tradeoff.csv").c_str());
  return kExitOk;
}

}  // namespace rayview
