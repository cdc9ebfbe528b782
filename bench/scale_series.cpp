// The scale series of docs/PERFORMANCE.md ("How to measure"): generated scenes from 1e3 to 1e7 triangles, where the
// memory goes, and the log-log plot. bench/scale_series.py drives it and times `rayview render` itself.
//
//   scale_series write KIND TRIANGLES OUT.xml [WIDTH HEIGHT]  KIND: sphere, heightfield or soup (1920x1080)
//   scale_series breakdown SCENE.xml [THREADS]   the steps of `rayview render`, resident memory after each
//   scale_series plot RESULTS.csv OUT.png        log-log time and memory against triangles
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "generated_scenes.h"
#include "rayview/plot_canvas.h"
#include "rayview/frame_renderer.h"
#include "rayview/prepared_scene.h"
#include "rayview/process_memory.h"
#include "rayview/scene_loader.h"
#include "rayview/scene_writer.h"

namespace rayview {
namespace {

int usage() {
  std::fprintf(stderr,
               "usage: scale_series write sphere|heightfield|soup TRIANGLES OUT.xml [WIDTH HEIGHT]\n"
               "       scale_series breakdown SCENE.xml [THREADS]\n"
               "       scale_series plot RESULTS.csv OUT.png\n");
  return 2;
}

int write(const std::string& kind, long long triangles, const std::string& out, int width, int height) {
  Scene scene;
  const int n = static_cast<int>(triangles);
  if (kind == "sphere") scene = bench::sphereScene(n, width, height);
  else if (kind == "heightfield") scene = bench::heightfieldScene(n, width, height);
  else if (kind == "soup") scene = bench::soupScene(n, width, height);
  else return usage();
  bench::roundCoordinates(scene);
  writeSceneFile(out, scene);
  std::printf("%s: %zu triangles, %zu vertices\n", out.c_str(), scene.triangles.size(), scene.vertices.size());
  return 0;
}

// Resident and peak resident memory of this process, in bytes (rayview/process_memory.h).
struct Memory {
  double rss = 0.0, peak = 0.0;
};
Memory memoryNow() {
  const ProcessMemory m = processMemory();
  return {static_cast<double>(m.resident), static_cast<double>(m.peak)};
}
// Resets VmHWM to the current RSS (Linux 4.0+), so each step's own transient peak can be read.
void resetPeak() {
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";
}

// What an array holds: its size, not its capacity. The loader reserves generously (from the text's length)
// so that blocks parse straight into place; reserved pages never written are not resident, and counting the
// capacity put the sphere's 1e7 arrays at 3.9 GB in a process whose whole peak was 2.4 GB.
template <class T, class Allocator>
double bytesOf(const std::vector<T, Allocator>& v) {
  return static_cast<double>(v.size() * sizeof(T));
}
double sceneArrayBytes(const SceneGeometry& s) {
  return bytesOf(s.vertices) + bytesOf(s.texCoords) + bytesOf(s.normals) + bytesOf(s.meshes) + bytesOf(s.triangles) +
         bytesOf(s.faceAttributes);
}

int breakdown(const std::string& path, int threads) {
  using Clock = std::chrono::steady_clock;
  const Memory start = memoryNow();
  resetPeak();
  auto t0 = Clock::now();
  LoadedScene loaded = loadSceneFile(path, LoadOptions{false, true});
  const double loadMs = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  const Memory afterLoad = memoryNow();
  // Shared, not copied, as `rayview render` does (app/render_command.cpp).
  const auto shared = std::make_shared<const Scene>(std::move(loaded.scene));
  const Scene& scene = *shared;
  const double n = static_cast<double>(scene.triangles.size());
  std::printf("%s: %zu triangles, %zu vertices, %zu normals; load %.0f ms\n", path.c_str(), scene.triangles.size(),
              scene.vertices.size(), scene.normals.size(), loadMs);
  std::printf("| step | resident after, MB | B/triangle | step's own peak above its start, MB | B/triangle |\n");
  std::printf("|---|---:|---:|---:|---:|\n");
  auto row = [&](const char* step, const Memory& before, const Memory& after) {
    std::printf("| %s | %.0f (+%.0f) | %.0f | %.0f | %.0f |\n", step, after.rss / 1e6, (after.rss - before.rss) / 1e6,
                (after.rss - before.rss) / n, (after.peak - before.rss) / 1e6, (after.peak - before.rss) / n);
  };
  row("load (file text, the big blocks read as a stream, the rest as a tinyxml2 DOM; Scene)", start, afterLoad);

  resetPeak();
  // The fast layout, which `rayview render` builds whenever it fits in the memory available.
  std::shared_ptr<const PreparedGeometry> geometry = prepareGeometry(shared, AccelKind::Embree, BvhBuild::OneImage);
  const Memory afterBuild = memoryNow();
  row("prepareGeometry (the BVH `rayview render` builds, shading geometry)", afterLoad, afterBuild);

  resetPeak();
  Image image;
  FrameStats stats;
  {
    ThreadPool pool(threads);
    const Tracer tracer(scene, *geometry->accel, geometry->shading, RenderSettings{});
    renderFrame(tracer, scene.camera.width, scene.camera.height, pool, image, stats);
  }
  const Memory afterRender = memoryNow();
  row("render (image, thread stacks)", afterBuild, afterRender);

  // What the arrays themselves take, from their sizes; the BVH's part is the build step's growth.
  const double sceneBytes = sceneArrayBytes(scene);
  // Shading and the Embree back-end's TriangleData hold nothing per triangle: they read the scene's arrays.
  const double bvhBytes = afterBuild.rss - afterLoad.rss;
  std::printf("\n| where the bytes go (held during the render) | MB | B/triangle |\n|---|---:|---:|\n");
  auto part = [&](const char* what, double bytes) { std::printf("| %s | %.0f | %.0f |\n", what, bytes / 1e6, bytes / n); };
  part("Scene arrays (vertices dvec3 24 B, Triangle 12 B, face attributes 24 B when a face has them, normals, meshes)",
       sceneBytes);
  part("the BVH and the rest of the build step (measured: the step's resident growth)", bvhBytes);
  part("image and the rest of the render step", afterRender.rss - afterBuild.rss);
  part("transient peak of the load above what it keeps (file text, tinyxml2 DOM)", afterLoad.peak - afterLoad.rss);
  std::printf("\nprocess peak (the highest of the steps' peaks; each step's VmHWM was reset at its start): "
              "%.0f MB = %.0f B/triangle\n",
              std::max({afterLoad.peak, afterBuild.peak, afterRender.peak}) / 1e6,
              std::max({afterLoad.peak, afterBuild.peak, afterRender.peak}) / n);
  return 0;
}

// --- the plot ---------------------------------------------------------------------------------------------

struct Series {
  std::string name;
  Rgb colour;
  MarkerShape shape;
  std::vector<std::pair<double, double>> points;  // (triangles, value)
  bool dashed = false;
};

void logLogPanel(PlotCanvas& c, double x0, double y0, double x1, double y1, const std::string& title,
                 const std::string& yLabel, const std::vector<Series>& series) {
  double xmin = 1e300, xmax = 0, ymin = 1e300, ymax = 0;
  for (const Series& s : series)
    for (auto [x, y] : s.points)
      if (x > 0 && y > 0) xmin = std::min(xmin, x), xmax = std::max(xmax, x), ymin = std::min(ymin, y), ymax = std::max(ymax, y);
  if (xmax <= 0) return;
  const double lx0 = std::floor(std::log10(xmin)), lx1 = std::ceil(std::log10(xmax));
  const double ly0 = std::floor(std::log10(ymin)), ly1 = std::max(ly0 + 1, std::ceil(std::log10(ymax)));
  const double left = x0 + 70, right = x1 - 10, top = y0 + 30, bottom = y1 - 45;
  auto px = [&](double x) { return left + (std::log10(x) - lx0) / (lx1 - lx0) * (right - left); };
  auto py = [&](double y) { return bottom - (std::log10(y) - ly0) / (ly1 - ly0) * (bottom - top); };
  const Rgb grid{220, 220, 220}, ink{40, 40, 40};
  for (double e = lx0; e <= lx1; ++e) {
    c.line(px(std::pow(10, e)), top, px(std::pow(10, e)), bottom, 1, grid);
    c.text(px(std::pow(10, e)), bottom + 8, "1e" + std::to_string(static_cast<int>(e)), 1.4, ink, TextAlign::Centre);
  }
  for (double e = ly0; e <= ly1; ++e) {
    c.line(left, py(std::pow(10, e)), right, py(std::pow(10, e)), 1, grid);
    c.text(left - 6, py(std::pow(10, e)) - 5, "1e" + std::to_string(static_cast<int>(e)), 1.4, ink, TextAlign::Right);
  }
  c.line(left, bottom, right, bottom, 1.5, ink);
  c.line(left, top, left, bottom, 1.5, ink);
  c.text((left + right) / 2, y0 + 4, title, 1.8, ink, TextAlign::Centre);
  c.text((left + right) / 2, bottom + 26, "triangles", 1.5, ink, TextAlign::Centre);
  c.verticalText(x0 + 14, (top + bottom) / 2, yLabel, 1.5, ink);
  double legendY = top + 6;
  for (const Series& s : series) {
    for (std::size_t i = 0; i + 1 < s.points.size(); ++i) {
      const auto [ax, ay] = s.points[i];
      const auto [bx, by] = s.points[i + 1];
      if (s.dashed) c.dashedLine(px(ax), py(ay), px(bx), py(by), 1.5, 6, s.colour);
      else c.line(px(ax), py(ay), px(bx), py(by), 2, s.colour);
    }
    if (!s.dashed)
      for (auto [x, y] : s.points) c.marker(px(x), py(y), 4, s.shape, s.colour);
    c.marker(left + 14, legendY + 5, 4, s.shape, s.colour);
    c.text(left + 24, legendY, s.name, 1.3, ink);
    legendY += 15;
  }
}

int plot(const std::string& csvPath, const std::string& out) {
  // kind,triangles,load_ms,build_ms,render_ms,peak_bytes
  std::ifstream csv(csvPath);
  std::string line;
  std::getline(csv, line);  // header
  std::map<std::string, std::vector<std::vector<double>>> rows;
  while (std::getline(csv, line)) {
    std::stringstream ss(line);
    std::string kind, cell;
    std::getline(ss, kind, ',');
    std::vector<double> values;
    while (std::getline(ss, cell, ',')) values.push_back(std::atof(cell.c_str()));
    if (values.size() >= 5) rows[kind].push_back(values);
  }
  const Rgb colours[] = {{0, 114, 178}, {213, 94, 0}, {0, 158, 115}};
  const MarkerShape shapes[] = {MarkerShape::Circle, MarkerShape::Square, MarkerShape::Triangle};
  const char* measures[] = {"load", "build", "render"};
  std::vector<Series> time, memory;
  int k = 0;
  double nmin = 1e300, nmax = 0;
  for (auto& [kind, points] : rows) {
    std::sort(points.begin(), points.end());
    for (int m = 0; m < 3; ++m) {
      Series s{kind + " " + measures[m], colours[m], shapes[k % 3], {}};
      for (const auto& p : points) s.points.push_back({p[0], p[1 + m]});
      time.push_back(s);
    }
    Series s{kind + " peak RSS", colours[k % 3], shapes[k % 3], {}};
    for (const auto& p : points) {
      s.points.push_back({p[0], p[4]});
      nmin = std::min(nmin, p[0]), nmax = std::max(nmax, p[0]);
    }
    memory.push_back(s);
    ++k;
  }
  if (nmax > 0) memory.push_back(Series{"200 B/triangle", {120, 120, 120}, MarkerShape::Circle, {{nmin, 200 * nmin}, {nmax, 200 * nmax}}, true});
  PlotCanvas canvas(1400, 620, Rgb{255, 255, 255});
  logLogPanel(canvas, 0, 0, 700, 620, "load, build, render time (1920x1080, 2 threads)", "ms", time);
  logLogPanel(canvas, 700, 0, 1400, 620, "peak resident memory of rayview render", "bytes", memory);
  writeImageFile(out, canvas.finish());
  std::printf("wrote %s\n", out.c_str());
  return 0;
}

}  // namespace
}  // namespace rayview

int main(int argc, char** argv) {
  using namespace rayview;
  if (argc < 2) return usage();
  const std::string command = argv[1];
  try {
    if (command == "write" && (argc == 5 || argc == 7))
      return write(argv[2], std::atoll(argv[3]), argv[4], argc == 7 ? std::atoi(argv[5]) : 1920,
                   argc == 7 ? std::atoi(argv[6]) : 1080);
    if (command == "breakdown" && (argc == 3 || argc == 4)) return breakdown(argv[2], argc == 4 ? std::atoi(argv[3]) : 2);
    if (command == "plot" && argc == 4) return plot(argv[2], argv[3]);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "scale_series: %s\n", error.what());
    return 1;
  }
  return usage();
}
