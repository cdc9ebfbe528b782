// The words for whose camera and lights a model is seen with, as the command line and the worker spell them.

#include <array>

#include "rayview/model_options.h"

namespace rayview {
namespace {

using Words = std::array<const char*, 3>;  // in ModelViewSource's order
constexpr Words kCameraWords = {"shown", "file", "auto"};
constexpr Words kLightWords = {"shown", "file", "kit"};

bool parseWord(const Words& words, const std::string& text, ModelViewSource& source) {
  for (std::size_t k = 0; k < words.size(); ++k)
    if (text == words[k]) {
      source = static_cast<ModelViewSource>(k);
      return true;
    }
  return false;
}

}  // namespace

bool parseModelCamera(const std::string& text, ModelViewSource& source) { return parseWord(kCameraWords, text, source); }
bool parseModelLights(const std::string& text, ModelViewSource& source) { return parseWord(kLightWords, text, source); }
std::string modelCameraWord(ModelViewSource source) { return kCameraWords[static_cast<std::size_t>(source)]; }
std::string modelLightsWord(ModelViewSource source) { return kLightWords[static_cast<std::size_t>(source)]; }

}  // namespace rayview
