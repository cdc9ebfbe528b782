#include "numbered_file.h"

#include <cstdio>
#include <system_error>
#include <unistd.h>

#include "rayview/scene_source.h"
#include "rayview/scene_writer.h"

namespace rayview {
namespace {

namespace fs = std::filesystem;

std::string numbered(int n) {
  char digits[16];
  std::snprintf(digits, sizeof digits, "_%03d", n);
  return digits;
}

}  // namespace

fs::path numberedFileBase(const std::string& scenePath) {
  if (scenePath.empty()) return fs::current_path() / "default";
  const fs::path scene = fs::absolute(scenePath);
  return scene.parent_path() / scene.stem();
}

fs::path writeNumberedFile(const fs::path& base, const std::string& extension,
                           const std::function<void(const fs::path&)>& write) {
  // The temporary keeps the real extension: the image writer picks the format from it.
  std::string temporaryName = base.filename().string();
  temporaryName.insert(temporaryName.begin(), '.');  // hidden while it is being written
  temporaryName += ".saving-" + std::to_string(::getpid()) + extension;
  const fs::path temporary = base.parent_path() / temporaryName;
  write(temporary);
  std::error_code ec;
  for (int n = 1; n <= kMaxNumberedFiles; ++n) {
    const fs::path target = base.parent_path() / (base.filename().string() + numbered(n) + extension);
    if (fs::exists(target, ec)) continue;
    fs::create_hard_link(temporary, target, ec);
    if (!ec) {
      fs::remove(temporary, ec);
      return target;
    }
    if (ec == std::errc::file_exists || fs::exists(target)) continue;  // taken between the check and the link
    // A file system without hard links: a rename into a name just seen free is the best left.
    fs::rename(temporary, target, ec);
    if (!ec) return target;
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw ImageIoError("cannot save " + target.string() + ": " + ec.message());
  }
  fs::remove(temporary, ec);
  throw ImageIoError("cannot save: " + std::to_string(kMaxNumberedFiles) + " numbered files already exist next to " +
                     base.string());
}

fs::path saveFrameNumbered(const Image& image, const std::string& scenePath, FrameSave what) {
  fs::path base = numberedFileBase(scenePath);
  if (what == FrameSave::Displayed) base += "_displayed";
  if (what == FrameSave::View) base += "_view";
  return writeNumberedFile(base, ".png", [&](const fs::path& temporary) { writeImageFile(temporary, image); });
}

fs::path saveSceneNumbered(const SceneParameters& parameters, const Scene& loaded, const std::string& scenePath) {
  const fs::path base = numberedFileBase(scenePath);
  return writeNumberedFile(fs::path(base.string() + "_edited"), ".xml", [&](const fs::path& temporary) {
    // The texture reference is computed for the final directory, which is the temporary's directory.
    writeSceneFile(temporary, parameters, loaded);
  });
}

const std::string& refusingInputs(const std::string& path, const std::string& scenePath, const Scene* loaded) {
  if (const std::string problem = outputOverwritesInput(path, scenePath, loaded); !problem.empty())
    throw ImageIoError(problem);
  return path;
}

}  // namespace rayview
