// PNG writing against render time, so that the write stays a small part of a render: rayview's encoder
// (renderer/png_encode.cpp: ISA-L at level 1, zlib above, in parallel parts) against stb_image_write's own, on the
// images the scenes render to, in one run.
//
// Usage: png_bench [--threads N] [--repeat R] SCENE.xml...
// For each scene: render it (renderFrame, N threads), then encode the image with each variant R times
// (median). Prints wall and process CPU ms, bytes and the shares of the render's; every rayview variant is decoded again and
// compared with the image (a mismatch exits 1).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "rayview/texture_image.h"

#include "rayview/frame_renderer.h"
#include "rayview/prepared_scene.h"
#include "rayview/scene_loader.h"
#include "stb_native_png.h"

namespace rayview {
namespace {

using Clock = std::chrono::steady_clock;

double medianOf(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

// CPU time of the whole process (all threads): on a shared, loaded machine it is far steadier than wall time.
double processCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

struct Timed {
  double ms = 0.0;
  double cpuMs = 0.0;
  std::size_t bytes = 0;
};

Timed timeIt(int repeat, const std::function<std::size_t()>& encode) {
  std::vector<double> ms, cpu;
  std::size_t bytes = 0;
  encode();  // warm-up
  for (int r = 0; r < repeat; ++r) {
    const auto start = Clock::now();
    const double cpuStart = processCpuMs();
    bytes = encode();
    cpu.push_back(processCpuMs() - cpuStart);
    ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
  }
  return {medianOf(ms), medianOf(cpu), bytes};
}

bool decodesTo(const std::string& png, const Image& image) {
  std::string reason;
  const std::optional<Texture> decoded = detail::decodeImage(png, reason);
  return decoded && decoded->width == image.width && decoded->height == image.height && decoded->rgb == image.rgb;
}

// The raw rows in `parts` parts, each deflated by stb on a thread of its own, not joined: the bytes of all parts.
std::size_t stbDeflateInParts(const Image& image, int parts) {
  const auto bytes = static_cast<int>(image.rgb.size());
  std::vector<std::thread> workers;
  std::vector<int> sizes(parts);
  for (int k = 0; k < parts; ++k)
    workers.emplace_back([&, k] {
      const int begin = static_cast<int>(static_cast<long long>(bytes) * k / parts);
      const int end = static_cast<int>(static_cast<long long>(bytes) * (k + 1) / parts);
      sizes[k] = bench::stbNativeDeflate(image.rgb.data() + begin, end - begin, 5);
    });
  std::size_t total = 0;
  for (int k = 0; k < parts; ++k) {
    workers[k].join();
    total += sizes[k];
  }
  return total;
}

}  // namespace
}  // namespace rayview

int main(int argc, char** argv) {
  using namespace rayview;
  int threads = 0, repeat = 5;
  std::vector<std::filesystem::path> scenes;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--threads" && i + 1 < argc) threads = std::atoi(argv[++i]);
    else if (arg == "--repeat" && i + 1 < argc) repeat = std::max(1, std::atoi(argv[++i]));
    else scenes.emplace_back(arg);
  }
  if (scenes.empty()) {
    std::fprintf(stderr, "usage: png_bench [--threads N] [--repeat R] SCENE.xml...\n");
    return 2;
  }
  ThreadPool pool(threads);
  const int n = pool.size();
  std::printf("%d render threads; encode: median of %d\n", n, repeat);
  int status = 0;
  for (const auto& path : scenes) {
    const Scene scene = loadSceneFile(path).scene;
    auto geometry = prepareGeometry(scene, AccelKind::Embree, BvhBuild::Interactive);
    const Tracer tracer(scene, *geometry->accel, geometry->shading, RenderSettings{});
    Image image;
    FrameStats stats;
    std::vector<double> renders, renderCpu;
    for (int r = 0; r < 3; ++r) {
      const double cpuStart = processCpuMs();
      renderFrame(tracer, scene.camera.width, scene.camera.height, pool, image, stats);
      renderCpu.push_back(processCpuMs() - cpuStart);
      renders.push_back(stats.renderMs);
    }
    const double renderMs = medianOf(renders), renderCpuMs = medianOf(renderCpu);
    std::printf("\n%s, %dx%d, render %.1f ms wall, %.1f ms CPU (median of 3)\n\n", path.stem().c_str(), image.width,
                image.height, renderMs, renderCpuMs);
    std::printf("| encoder | ms wall | ms CPU | bytes | wall %% of render wall | CPU %% of render CPU |\n"
                "|---|---:|---:|---:|---:|---:|\n");
    auto row = [&](const std::string& name, const Timed& t) {
      std::printf("| %s | %.1f | %.1f | %zu | %.1f %% | %.1f %% |\n", name.c_str(), t.ms, t.cpuMs, t.bytes,
                  100.0 * t.ms / renderMs, 100.0 * t.cpuMs / renderCpuMs);
      std::fflush(stdout);
    };
    row("stb (before): best-of-5 filter per row, stb deflate level 8",
        timeIt(repeat, [&] { return bench::stbNativePng(image, 8, -1).size(); }));
    row("stb: best-of-5 filter, stb deflate level 5 (its fastest)",
        timeIt(repeat, [&] { return bench::stbNativePng(image, 5, -1).size(); }));
    for (int filter : {0, 1, 2, 4})
      row("stb: filter " + std::to_string(filter) + " on every row, stb deflate level 5",
          timeIt(repeat, [&] { return bench::stbNativePng(image, 5, filter).size(); }));
    // stb's deflate cannot be split into parts and spliced (it ends in a final block with unknown bit
    // padding), so this is only a lower bound for a parallel stb deflate.
    const int parts = std::max(1, std::min(n, static_cast<int>(image.rgb.size()) / (1 << 18)));
    row("lower bound: stb deflate level 5 of the raw rows, " + std::to_string(parts) + " parts on threads, not joined",
        timeIt(repeat, [&] { return stbDeflateInParts(image, parts); }));
    for (int level : {1, 3, 6})
      for (int t : {1, n}) {
        if (t == 1 && n == 1 && level != 1) continue;
        const PngOptions options{level, t};
        const std::string png = encodePng(image, options);
        if (!decodesTo(png, image)) {
          std::fprintf(stderr, "png_bench: level %d, %d threads: does not decode to the image\n", level, t);
          status = 1;
        }
        row(std::string("rayview: unfiltered rows, ") + (level == 1 ? "ISA-L" : "zlib") + " level " +
                std::to_string(level) + ", " + std::to_string(t) +
                " thread" + (t == 1 ? "" : "s") + (level == kDefaultPngLevel && t == n ? " (default)" : ""),
            timeIt(repeat, [&] { return encodePng(image, options).size(); }));
      }
  }
  return status;
}
