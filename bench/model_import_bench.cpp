// model_import_bench [--triangles N] [--dir DIR]: writes a binary PLY of about N triangles (a bumpy grid; default
// 1e6) and measures, each in a child process of its own (time, and the child's peak resident memory, VmHWM):
//   own      rayview's PLY reader (rayview_import, readModelGeometry);
//   assimp   Assimp's reader of the same file (the geometry only, the same way);
//   worker   the import worker answering rayview (reading, framing, the answer written to /dev/null);
//   import   `rayview import FILE.ply -o FILE.xml` end to end (its own peak; the worker's is the line above).
// Then the same grid as a binary STL, own reader against Assimp's. docs/dependencies.md records the figures.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "rayview/model_import.h"
#include "rayview/process_memory.h"

namespace {

namespace fs = std::filesystem;

void writeGridPly(const fs::path& path, long long triangles) {
  const int n = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(triangles) / 2.0)));
  std::ofstream out(path, std::ios::binary);
  out << "ply\nformat binary_little_endian 1.0\nelement vertex " << (n + 1) * (n + 1)
      << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << 2LL * n * n
      << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const float v[3] = {static_cast<float>(i) / n, 0.05f * std::sin(i * 0.05f) * std::cos(j * 0.07f),
                          static_cast<float>(j) / n};
      out.write(reinterpret_cast<const char*>(v), sizeof v);
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      const int faces[2][3] = {{a, c, b}, {b, c, d}};
      for (const auto& f : faces) {
        const unsigned char three = 3;
        out.write(reinterpret_cast<const char*>(&three), 1);
        out.write(reinterpret_cast<const char*>(f), sizeof f);
      }
    }
  std::printf("file     %s: %lld triangles, %.1f MiB\n", path.c_str(), 2LL * n * n,
              static_cast<double>(fs::file_size(path)) / (1024.0 * 1024.0));
}

// The same grid as a binary STL (a triangle soup: three corners per triangle).
void writeGridStl(const fs::path& path, long long triangles) {
  const int n = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(triangles) / 2.0)));
  std::ofstream out(path, std::ios::binary);
  out << std::string(80, ' ');
  const auto count = static_cast<std::uint32_t>(2LL * n * n);
  out.write(reinterpret_cast<const char*>(&count), 4);
  auto corner = [n](int i, int j, float* v) {
    v[0] = static_cast<float>(i) / n;
    v[1] = 0.05f * std::sin(i * 0.05f) * std::cos(j * 0.07f);
    v[2] = static_cast<float>(j) / n;
  };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int faces[2][3][2] = {{{i, j}, {i, j + 1}, {i + 1, j}}, {{i + 1, j}, {i, j + 1}, {i + 1, j + 1}}};
      for (const auto& f : faces) {
        float record[12] = {};
        for (int k = 0; k < 3; ++k) corner(f[k][0], f[k][1], record + 3 + 3 * k);
        out.write(reinterpret_cast<const char*>(record), sizeof record);
        out.write("\0\0", 2);
      }
    }
  std::printf("file     %s: %u triangles, %.1f MiB\n", path.c_str(), count,
              static_cast<double>(fs::file_size(path)) / (1024.0 * 1024.0));
}

// Runs `work` in a forked child; prints its time and the child's peak resident memory.
template <class Work>
void measureInChild(const char* label, Work work) {
  int fds[2];
  std::fflush(stdout);  // a fork would print what is buffered twice
  if (::pipe(fds) != 0) return;
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(fds[0]);
    const auto start = std::chrono::steady_clock::now();
    std::string note;
    try {
      note = work();
    } catch (const std::exception& e) {
      note = std::string("failed: ") + e.what();
    }
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    char line[512];
    const int length = std::snprintf(line, sizeof line, "%-8s %8.1f ms, peak %7.1f MiB  %s\n", label, ms,
                                     static_cast<double>(rayview::processMemory().peak) / (1024.0 * 1024.0), note.c_str());
    if (::write(fds[1], line, static_cast<std::size_t>(length)) < 0) _exit(1);
    _exit(0);
  }
  ::close(fds[1]);
  char buffer[512] = {};
  const ssize_t got = ::read(fds[0], buffer, sizeof buffer - 1);
  ::close(fds[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  std::fputs(got > 0 ? buffer : "(no answer)\n", stdout);
}

// Runs a program to completion with stdout to /dev/null; its time and peak (ru_maxrss, which is VmHWM).
void measureProgram(const char* label, std::vector<std::string> argv) {
  std::fflush(stdout);
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid == 0) {
    std::freopen("/dev/null", "w", stdout);
    std::vector<char*> args;
    for (std::string& a : argv) args.push_back(a.data());
    args.push_back(nullptr);
    ::execv(args[0], args.data());
    _exit(127);
  }
  int status = 0;
  rusage usage{};
  ::wait4(pid, &status, 0, &usage);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  std::printf("%-8s %8.1f ms, peak %7.1f MiB  exit %d\n", label, ms, static_cast<double>(usage.ru_maxrss) / 1024.0,
              WIFEXITED(status) ? WEXITSTATUS(status) : -1);
}

}  // namespace

int main(int argc, char** argv) {
  long long triangles = 1000000;
  fs::path dir = fs::temp_directory_path() / "rayview_model_bench";
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--triangles") == 0) triangles = std::atoll(argv[i + 1]);
    else if (std::strcmp(argv[i], "--dir") == 0) dir = argv[i + 1];
  }
  fs::create_directories(dir);
  const fs::path ply = dir / "grid.ply";
  writeGridPly(ply, triangles);
  auto count = [](const rayview::SceneGeometry& g) { return std::to_string(g.triangles.size()) + " triangles"; };
  measureInChild("own", [&] { return count(rayview::readModelGeometry(ply, false)); });
  measureInChild("assimp", [&] { return count(rayview::readModelGeometry(ply, true)); });
  measureProgram("worker", {RAYVIEW_IMPORT_WORKER, "read", ply.string()});
  measureProgram("import", {RAYVIEW_EXECUTABLE, "import", ply.string(), "-o", (dir / "grid.xml").string()});
  const fs::path stl = dir / "grid.stl";
  writeGridStl(stl, triangles);
  measureInChild("own", [&] { return count(rayview::readModelGeometry(stl, false)); });
  measureInChild("assimp", [&] { return count(rayview::readModelGeometry(stl, true)); });
  return 0;
}
