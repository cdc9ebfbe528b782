#pragma once
// The viewer's automation language (`rayview SCENE --script FILE`, documented in docs/viewer.md): one
// command per line; lines starting with `#` are comments. Parsing checks every line before the window
// opens, so a typo fails at once with "FILE:LINE: ..." instead of halfway through a test.

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace rayview {

class ScriptError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ScriptCommand {
  int line = 0;
  std::string name;               // "wait-final", "set", "camera", ...
  std::vector<std::string> args;  // tokens after the name; for commands taking a path or text, one argument: the rest of the line
  std::vector<double> numbers;    // the numeric arguments, already checked

  std::string where(const std::string& file) const { return file + ":" + std::to_string(line); }
};

struct Script {
  std::string file;
  std::vector<ScriptCommand> commands;
};

// The largest script read (a soak test's 10 000 commands take well under 1 MiB).
inline constexpr std::uintmax_t kMaxScriptBytes = 64ull * 1024 * 1024;

// Throws ScriptError with "FILE:LINE: message".
Script parseScript(const std::string& text, const std::string& file);
Script readScriptFile(const std::filesystem::path& path);

// Default time limits, in seconds.
inline constexpr double kDefaultWaitFinalSeconds = 120.0;
inline constexpr double kDefaultLoadSeconds = 300.0;
inline constexpr double kDefaultTradeoffSeconds = 600.0;
// The longest time a script may give (about 11.6 days): far below where a deadline overflows the clock (~9e9 s).
inline constexpr double kMaxScriptSeconds = 1e6;
// measure-tradeoff without a scale measures at this share of the image's resolution (as the panel's default).
inline constexpr double kDefaultTradeoffScale = 0.25;

}  // namespace rayview
