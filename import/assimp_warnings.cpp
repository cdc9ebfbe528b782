// Listening to Assimp's logger (assimp_warnings.h) for the messages that mean a file is broken.

#include "assimp_warnings.h"

#include <assimp/DefaultLogger.hpp>
#include <assimp/LogStream.hpp>

#include <algorithm>
#include <cctype>
#include <string_view>

namespace rayview::model {

struct AssimpWarnings::Stream : Assimp::LogStream {
  std::string broken;
  void write(const char* message) override {
    if (!broken.empty() || !message) return;
    std::string lower(message);
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
    // What Assimp 5's readers say when they skip or clamp an index, or read fewer records than a header declares.
    static constexpr std::string_view kBroken[] = {"out-of-range", "out of range", "out of bounds",
                                                   "in the header is incorrect", "invalid index"};
    for (std::string_view words : kBroken)
      if (lower.find(words) != std::string::npos) {
        broken = message;
        // Without the logger's "Warn,  T0: " prefix.
        if (const std::size_t colon = broken.find(": "); colon != std::string::npos && colon < 16)
          broken.erase(0, colon + 2);
        while (!broken.empty() && std::isspace(static_cast<unsigned char>(broken.back()))) broken.pop_back();
        return;
      }
  }
};

AssimpWarnings::AssimpWarnings() : stream_(std::make_unique<Stream>()) {
  Assimp::DefaultLogger::create("", Assimp::Logger::NORMAL, 0);
  Assimp::DefaultLogger::get()->attachStream(stream_.get(), Assimp::Logger::Warn | Assimp::Logger::Err);
}

AssimpWarnings::~AssimpWarnings() {
  // Detached first: the logger would otherwise delete the stream, which is ours.
  Assimp::DefaultLogger::get()->detachStream(stream_.get(), Assimp::Logger::Warn | Assimp::Logger::Err);
  Assimp::DefaultLogger::kill();
}

std::string AssimpWarnings::brokenData() const { return stream_->broken; }

}  // namespace rayview::model
