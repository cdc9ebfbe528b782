// Reading a CSE 461 PA1 scene: repair pass, tinyxml2, then a case-insensitive walk that fills Scene.
// Every message a user can meet is listed in docs/scene-format.md; keep the two in step.
// This file: the entry points. The loader's three jobs live in scene_loader_elements.cpp (element
// readers), scene_loader_walk.cpp (the walk) and scene_loader_checks.cpp (checks after the walk).

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include "scene_loader_internal.h"

namespace rayview {

namespace scene_loading {

LoadedScene Loader::load(std::string_view text) {
  detail::RepairedXml repaired = detail::repairXml(text, file_, options_.strict);
  for (Diagnostic& d : repaired.repairs) warnings_.add(std::move(d));
  std::string_view xml = repaired.changed ? std::string_view(repaired.text) : text;

  tinyxml2::XMLDocument doc(true, tinyxml2::PRESERVE_WHITESPACE);
  if (doc.Parse(xml.data(), xml.size()) != tinyxml2::XML_SUCCESS) xmlError(doc);

  const XMLElement* root = doc.RootElement();
  if (!root) fail(0, "no <scene> element: the file has no elements");
  detectCeng477(root);
  if (!isName(root, "scene"))
    fail(root->GetLineNum(), "the root element is <" + std::string(root->Name()) + ">, expected <scene>");
  for (const XMLNode* node = root->NextSibling(); node; node = node->NextSibling()) {
    if (const XMLElement* extra = node->ToElement()) unknownElement(extra, "after </scene>");
    if (const tinyxml2::XMLText* text = node->ToText()) strayText(text);
  }
  for (const XMLNode* node = doc.FirstChild(); node && node != root; node = node->NextSibling())
    if (const tinyxml2::XMLText* text = node->ToText()) strayText(text);

  readScene(root);
  finish(root);
  result_.warnings = warnings_.take();
  return std::move(result_);
}

}  // namespace scene_loading

namespace fs = std::filesystem;
using scene_loading::Loader;
using scene_loading::kMaxFileBytes;

LoadedScene loadSceneText(std::string_view xml, const std::string& displayName, const fs::path& baseDirectory,
                          const LoadOptions& options) {
  try {
    return Loader(displayName, baseDirectory, options).load(xml);
  } catch (const SceneError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throwSceneError({displayName, 0}, "out of memory while reading the scene");
  }
}

LoadedScene loadSceneFile(const fs::path& path, const LoadOptions& options) {
  const std::string display = path.string();
  std::error_code ec;
  if (fs::is_directory(path, ec)) throwSceneError({display, 0}, "cannot read the scene file: it is a directory");
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) throwSceneError({display, 0}, std::string("cannot open the scene file: ") + std::strerror(errno));
  std::string text;
  const std::uintmax_t size = fs::file_size(path, ec);
  if (!ec && size > kMaxFileBytes)
    throwSceneError({display, 0}, "the scene file is too large (" + std::to_string(size) + " bytes; the limit is 2 GiB)");
  if (!ec) text.reserve(static_cast<std::size_t>(size));
  char buffer[1 << 16];
  std::size_t got;
  while ((got = std::fread(buffer, 1, sizeof buffer, file.get())) > 0) {
    text.append(buffer, got);
    if (text.size() > kMaxFileBytes) throwSceneError({display, 0}, "the scene file is too large (the limit is 2 GiB)");
  }
  if (std::ferror(file.get())) throwSceneError({display, 0}, "cannot read the scene file");
  file.reset();
  fs::path directory = path.parent_path();
  LoadedScene loaded = loadSceneText(text, display, directory.empty() ? fs::path(".") : directory, options);
  loaded.scene.sourcePath = path;
  return loaded;
}

}  // namespace rayview
