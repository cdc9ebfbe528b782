// Reading a CSE 461 PA1 scene (or the METU CENG477 dialect, scene_loader_ceng477.cpp): repair pass, tinyxml2, then a case-insensitive walk that fills Scene.
// Every message a user can meet is listed in docs/scene-format.md; keep the two in step.
// This file: the entry points. The loader's three jobs live in scene_loader_elements.cpp (element
// readers), scene_loader_walk.cpp (the walk) and scene_loader_checks.cpp (checks after the walk).

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>

#include "rayview/file_read.h"
#include "scene_loader_internal.h"

namespace rayview {

namespace scene_loading {

// A binary file or one in another encoding is named for what it is, before any XML message about '<'.
void refuseWhatIsNotText(const std::string& file, std::string_view text) {
  if (std::string kind = detail::binaryFileKind(text.substr(0, detail::kFileStartBytes)); !kind.empty())
    throwSceneError({file, 0}, "the file " + kind);
  if (const void* nul = std::memchr(text.data(), '\0', text.size()))
    throwSceneError({file, 1 + detail::countNewlines(text.data(), static_cast<const char*>(nul))},
                    "the file contains NUL bytes: a binary file, not a scene file");
}

namespace {

// Parses the file at `path` with tinyxml2 reading it into its own buffer, when it is still `expectedSize` bytes;
// false (the document untouched) when it cannot be opened or its size changed since it was read.
bool parseFileDirectly(tinyxml2::XMLDocument& doc, const fs::path& path, std::size_t expectedSize, std::string& text) {
  // Opened as the one reader of user files opens (file_read.h): never blocking, should the path have become a FIFO
  // since it was read.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) return false;
  struct stat status {};
  if (::fstat(fd, &status) != 0 || !S_ISREG(status.st_mode) || static_cast<std::size_t>(status.st_size) != expectedSize) {
    ::close(fd);
    return false;
  }
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(::fdopen(fd, "rb"), &std::fclose);
  if (!file) {
    ::close(fd);
    return false;
  }
  std::string().swap(text);  // the copy already read: tinyxml2 makes its own
  doc.LoadFile(file.get());
  return true;
}

}  // namespace

LoadedScene Loader::load(std::string_view text, std::string* owned, const fs::path* source) {
  refuseWhatIsNotText(file_, text);
  detail::RepairedXml repaired = detail::repairXml(text, file_, options_.strict);
  for (Diagnostic& d : repaired.repairs) warnings_.add(std::move(d));
  std::string_view xml = repaired.changed ? std::string_view(repaired.text) : text;

  tinyxml2::XMLDocument doc(true, tinyxml2::PRESERVE_WHITESPACE);
  const bool direct = !repaired.changed && owned && source && !text.empty() &&
                      parseFileDirectly(doc, *source, text.size(), *owned);
  if (direct && doc.Error()) {
    // Messages quote the text: read it again (errors are rare; their memory does not matter).
    detail::UserFileRead again = detail::readUserFile(*source, kMaxFileBytes, {}, kSceneFileRole);
    if (!again.problem.empty()) fail(0, "the scene file " + again.problem);
    *owned = std::move(again.bytes);
    text = *owned;
    xml = text;
    if (doc.Parse(xml.data(), xml.size()) != tinyxml2::XML_SUCCESS) xmlError(doc, text);
  } else if (!direct && doc.Parse(xml.data(), xml.size()) != tinyxml2::XML_SUCCESS) {
    xmlError(doc, text);
  }
  // tinyxml2 parsed a copy of its own: the texts are not read again (messages take their lines from the DOM).
  std::string().swap(repaired.text);
  if (owned) std::string().swap(*owned);
  text = {};
  xml = {};
  return walk(doc);
}

LoadedScene Loader::walk(const tinyxml2::XMLDocument& doc) {
  const XMLElement* root = doc.RootElement();
  if (!root) fail(0, "no <scene> element: the file has no elements");
  ceng477_ = isCeng477(root);
  if (!isName(root, "scene"))
    fail(root->GetLineNum(), "the root element is <" + std::string(root->Name()) + ">, expected <scene>");
  for (const XMLNode* node = root->NextSibling(); node; node = node->NextSibling()) {
    if (const XMLElement* extra = node->ToElement()) unknownElement(extra, "after </scene>");
    if (const tinyxml2::XMLText* text = node->ToText()) strayText(text);
  }
  for (const XMLNode* node = doc.FirstChild(); node && node != root; node = node->NextSibling())
    if (const tinyxml2::XMLText* text = node->ToText()) strayText(text);

  if (ceng477_) readCeng477Scene(root);
  else readScene(root);
  if (options_.camera > 1 && !ceng477_)
    fail(cameraLine_ ? cameraLine_ : root->GetLineNum(),
         "camera " + std::to_string(options_.camera) + " was asked for, but the file has one <camera> (only CENG477 "
         "files have several)");
  // Faces from the stream that no mesh took (a <faces> out of place) would shift every later mesh's.
  if (streamed_ && claimedTriangles_ != streamed_->triangleCount) throw StreamAbandoned{};
  if (ceng477_) finishCeng477();
  finish(root);
  result_.warnings = warnings_.take();
  return std::move(result_);
}

}  // namespace scene_loading

namespace fs = std::filesystem;
using scene_loading::Loader;
using scene_loading::kMaxFileBytes;
using scene_loading::kSceneFileRole;

namespace {

// A scene too large for memory is a located message too, never a crash.
LoadedScene loadReportingMemory(std::string_view xml, std::string* owned, const fs::path* source,
                                const std::string& displayName, const fs::path& baseDirectory,
                                const LoadOptions& options) {
  try {
    return Loader(displayName, baseDirectory, options).load(xml, owned, source);
  } catch (const SceneError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throwSceneError({displayName, 0}, "out of memory while reading the scene");
  }
}

// The big blocks as a stream (scene_loader_internal.h); nothing when the ordinary reading must decide: it
// then reads the file again, so every message and warning is its own.
std::optional<LoadedScene> loadStreamed(const scene_loading::ReadAt& read, std::uint64_t size, const std::string& displayName,
                                        const fs::path& baseDirectory, const LoadOptions& options) {
  if (!options.streamBlocks) return std::nullopt;
  try {
    scene_loading::StreamedBlocks streamed = scene_loading::streamSkeleton(read, size);
    Loader::parseStreamedBlocks(streamed, read, options.threads);
    return Loader(displayName, baseDirectory, options).loadStreamed(streamed);
  } catch (const scene_loading::StreamAbandoned&) {
  } catch (const SceneError&) {
  } catch (const std::bad_alloc&) {
  }
  return std::nullopt;
}

}  // namespace

LoadedScene loadSceneText(std::string_view xml, const std::string& displayName, const fs::path& baseDirectory,
                          const LoadOptions& options) {
  const auto read = [xml](std::uint64_t offset, char* into, std::size_t count) -> long {
    if (offset >= xml.size()) return 0;
    const std::size_t n = std::min<std::uint64_t>(count, xml.size() - offset);
    std::memcpy(into, xml.data() + offset, n);
    return static_cast<long>(n);
  };
  if (std::optional<LoadedScene> streamed = loadStreamed(read, xml.size(), displayName, baseDirectory, options))
    return std::move(*streamed);
  return loadReportingMemory(xml, nullptr, nullptr, displayName, baseDirectory, options);
}

LoadedScene loadSceneFile(const fs::path& path, const LoadOptions& options) {
  const std::string display = path.string();
  fs::path directory = path.parent_path();
  if (directory.empty()) directory = ".";
  {
    // Opened with readUserFile's checks; any problem is reported by the ordinary reading below.
    const detail::UserFile file(path, kMaxFileBytes, kSceneFileRole);
    if (file.problem().empty()) {
      const auto read = [&file](std::uint64_t offset, char* into, std::size_t count) {
        return file.read(offset, into, count);
      };
      if (std::optional<LoadedScene> streamed = loadStreamed(read, file.size(), display, directory, options)) {
        streamed->scene.sourcePath = path;
        return std::move(*streamed);
      }
    }
  }
  // The start of the file is checked before the rest is read: a large binary file is refused at once.
  detail::UserFileRead file = detail::readUserFile(path, kMaxFileBytes, [&](std::string_view start) {
    scene_loading::refuseWhatIsNotText(display, start);
    return std::string();
  }, kSceneFileRole);
  if (file.notFound || file.problem.rfind("cannot be opened", 0) == 0)
    throwSceneError({display, 0}, "cannot open the scene file: " + file.problem.substr(file.problem.find(": ") + 2));
  if (!file.problem.empty()) throwSceneError({display, 0}, "the scene file " + file.problem);
  // The file's text is handed over, to be released as soon as it is parsed.
  LoadedScene loaded = loadReportingMemory(file.bytes, &file.bytes, &path, display, directory, options);
  loaded.scene.sourcePath = path;
  return loaded;
}

}  // namespace rayview
