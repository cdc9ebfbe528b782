#include "automation_script.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "display_mapping.h"
#include "rayview/file_read.h"
#include "rayview/knobs.h"
#include "rayview/light_types.h"
#include "rayview/scene_writer.h"

namespace rayview {
namespace {

std::string trim(const std::string& s) {
  const auto begin = s.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return {};
  return s.substr(begin, s.find_last_not_of(" \t\r") - begin + 1);
}

// Whitespace-separated words; "double quotes" keep spaces (for ids like "my light").
std::vector<std::string> tokenize(const std::string& text, std::string& error) {
  std::vector<std::string> tokens;
  std::size_t i = 0;
  while (i < text.size()) {
    if (text[i] == ' ' || text[i] == '\t' || text[i] == '\r') {
      ++i;
      continue;
    }
    std::string token;
    if (text[i] == '"') {
      const auto close = text.find('"', i + 1);
      if (close == std::string::npos) {
        error = "unterminated quote";
        return {};
      }
      token = text.substr(i + 1, close - i - 1);
      i = close + 1;
    } else {
      while (i < text.size() && text[i] != ' ' && text[i] != '\t' && text[i] != '\r') token += text[i++];
    }
    tokens.push_back(token);
  }
  return tokens;
}

class LineParser {
 public:
  LineParser(ScriptCommand& command, const std::string& file) : command_(command), file_(file) {}

  [[noreturn]] void fail(const std::string& message) const {
    throw ScriptError(command_.where(file_) + ": " + message);
  }

  double number(const std::string& token) const {
    double value = 0.0;
    const char* begin = token.data();
    if (!token.empty() && token[0] == '+') ++begin;
    const auto [end, error] = std::from_chars(begin, token.data() + token.size(), value);
    if (error != std::errc() || end != token.data() + token.size() || !std::isfinite(value))
      fail("'" + command_.name + "' expects a number, not '" + token + "'");
    return value;
  }

  // Takes exactly `count` numbers from tokens[from...] (and nothing after them).
  void numbers(const std::vector<std::string>& tokens, std::size_t from, std::size_t count, const std::string& usage) {
    if (tokens.size() != from + count) fail("usage: " + usage);
    for (std::size_t i = from; i < tokens.size(); ++i) command_.numbers.push_back(number(tokens[i]));
  }

  void integers(const std::vector<std::string>& tokens, std::size_t from, std::size_t count, const std::string& usage,
                double low, double high) {
    numbers(tokens, from, count, usage);
    for (const double v : command_.numbers)
      if (v != std::floor(v) || v < low || v > high)
        fail("'" + command_.name + "' expects whole numbers from " + std::to_string(static_cast<long long>(low)) +
             " to " + std::to_string(static_cast<long long>(high)) + " (" + usage + ")");
  }

  void optionalNumber(const std::vector<std::string>& tokens, const std::string& usage) {
    if (tokens.size() > 1) fail("usage: " + usage);
    for (const std::string& t : tokens) command_.numbers.push_back(number(t));
  }

 private:
  ScriptCommand& command_;
  const std::string& file_;
};

void parseSet(ScriptCommand& c, const std::vector<std::string>& t, LineParser& p) {
  if (t.empty()) {
    std::string names;
    for (const Knob& knob : knobTable()) names += std::string(knob.name) + ", ";
    p.fail("'set' needs what to set: " + names + "background, ambient, material, light, exposure, gamma");
  }
  const std::string& what = t[0];
  c.args = {what};
  // Display settings, not render knobs: they change how the image is shown, never what is rendered.
  if (what == "exposure" || what == "gamma") {
    const bool exposure = what == "exposure";
    const std::string usage = exposure ? "set exposure STOPS" : "set gamma GAMMA";
    p.numbers(t, 1, 1, usage);
    // In float, the type the viewer keeps them in: `set gamma 0.2` is the limit itself.
    const float value = static_cast<float>(c.numbers[0]);
    const float low = exposure ? kMinExposureStops : kMinGamma, high = exposure ? kMaxExposureStops : kMaxGamma;
    if (!(value >= low && value <= high))
      p.fail("'" + usage + "' takes " + formatNumber(low) + " to " + formatNumber(high) + ", not " + t[1]);
    return;
  }
  // The render knobs (rayview/knobs.h): `set NAME VALUE`, checked against the knob's own limits or choices.
  if (const Knob* knob = findKnob(what)) {
    const std::string usage = "set " + what + " " + knob->valueName();
    if (!knob->isChoice()) return p.integers(t, 1, 1, usage, knob->min, knob->max);
    const std::optional<int> value = t.size() == 2 ? knob->parse(t[1]) : std::nullopt;
    if (!value) p.fail("usage: " + usage);
    c.args.push_back(t[1]);
    c.numbers.push_back(*value);
    return;
  }
  if (what == "background" || what == "ambient") return p.numbers(t, 1, 3, "set " + what + " R G B");
  if (what == "material") {
    const std::string usage = "set material ID ambient|diffuse|specular|mirror R G B, or set material ID phong|texture-factor X";
    if (t.size() < 3) p.fail("usage: " + usage);
    c.args = {what, t[1], t[2]};
    const std::string& property = t[2];
    if (property == "ambient" || property == "diffuse" || property == "specular" || property == "mirror")
      return p.numbers(t, 3, 3, usage);
    if (property == "phong" || property == "texture-factor") return p.numbers(t, 3, 1, usage);
    p.fail("unknown material property '" + property + "' (" + usage + ")");
  }
  if (what == "light") {
    const std::string properties = lightPropertyNames();
    const std::string usage = "set light ID " + properties + " X Y Z";
    if (t.size() < 3) p.fail("usage: " + usage);
    c.args = {what, t[1], t[2]};
    const std::string& property = t[2];
    if (isLightProperty(property)) return p.numbers(t, 3, 3, usage);
    p.fail("unknown light property '" + property + "' (" + usage + ")");
  }
  p.fail("cannot set '" + what + "'");
}

void parseCamera(ScriptCommand& c, const std::vector<std::string>& t, LineParser& p) {
  if (t.empty()) p.fail("'camera' needs an action: orbit, pan, dolly, frame, reset, position, gaze, up, near-plane, near-distance, resolution");
  const std::string& what = t[0];
  c.args = {what};
  if (what == "orbit") return p.numbers(t, 1, 2, "camera orbit YAW_DEGREES PITCH_DEGREES");
  if (what == "pan") return p.numbers(t, 1, 2, "camera pan RIGHT UP (in view heights)");
  if (what == "dolly") return p.numbers(t, 1, 1, "camera dolly WHEEL_STEPS");
  if (what == "frame" || what == "reset") return p.numbers(t, 1, 0, "camera " + what);
  if (what == "position" || what == "gaze" || what == "up") return p.numbers(t, 1, 3, "camera " + what + " X Y Z");
  if (what == "near-plane") return p.numbers(t, 1, 4, "camera near-plane L R B T");
  if (what == "near-distance") return p.numbers(t, 1, 1, "camera near-distance D");
  if (what == "resolution") return p.integers(t, 1, 2, "camera resolution WIDTH HEIGHT", 1, 16384);
  p.fail("unknown camera action '" + what + "'");
}

// measure-tradeoff [SCALE] [TIMEOUT_SECONDS]: numbers[0] the scale, numbers[1] the timeout, defaults filled in.
void parseMeasureTradeoff(ScriptCommand& c, const std::vector<std::string>& t, LineParser& p) {
  const std::string usage = "measure-tradeoff [RESOLUTION_SCALE] [TIMEOUT_SECONDS]";
  if (t.size() > 2) p.fail("usage: " + usage);
  c.numbers = {kDefaultTradeoffScale, kDefaultTradeoffSeconds};
  for (std::size_t i = 0; i < t.size(); ++i) c.numbers[i] = p.number(t[i]);
  if (!(c.numbers[0] > 0.0 && c.numbers[0] <= 1.0))
    p.fail("the resolution scale must be above 0 and at most 1 (" + usage + ")");
  if (!(c.numbers[1] > 0.0)) p.fail("measure-tradeoff needs a positive timeout (" + usage + ")");
}

// tradeoff-apply advice | tradeoff-apply NAME VALUE: args[0] "advice" or the knob's name, numbers[0] its value.
void parseTradeoffApply(ScriptCommand& c, const std::vector<std::string>& t, LineParser& p) {
  std::string names;
  for (const Knob& knob : knobTable()) {
    if (!knob.measuredByTradeoff()) continue;
    if (!names.empty()) names += '|';
    names += knob.name;
  }
  const std::string usage = "tradeoff-apply advice, or tradeoff-apply " + names + " VALUE";
  if (t.size() == 1 && t[0] == "advice") {
    c.args = {t[0]};
    return;
  }
  const Knob* knob = t.size() == 2 ? findKnob(t[0]) : nullptr;
  if (!knob || !knob->measuredByTradeoff()) p.fail("usage: " + usage);
  const std::optional<int> value = knob->parse(t[1]);
  if (!value) p.fail("tradeoff-apply " + t[0] + " expects " + knob->expectation() + " (" + usage + ")");
  c.args = {t[0], t[1]};
  c.numbers = {static_cast<double>(*value)};
}

}  // namespace

Script parseScript(const std::string& text, const std::string& file) {
  Script script;
  script.file = file;
  std::istringstream in(text);
  std::string raw;
  int lineNumber = 0;
  while (std::getline(in, raw)) {
    ++lineNumber;
    // Whole-line comments only: paths and expected texts may contain '#'.
    const std::string line = trim(raw);
    if (line.empty() || line[0] == '#') continue;
    ScriptCommand c;
    c.line = lineNumber;
    const auto space = line.find_first_of(" \t");
    c.name = line.substr(0, space);
    const std::string rest = space == std::string::npos ? std::string() : trim(line.substr(space));
    LineParser p(c, file);

    // Commands whose argument is a path or free text: the rest of the line, spaces included.
    if (c.name == "open" || c.name == "screenshot" || c.name == "expect-error" || c.name == "compare") {
      if (rest.empty()) p.fail("'" + c.name + "' needs " + (c.name == "expect-error" ? "the text to expect" : "a path"));
      c.args = {rest};
    } else if (c.name == "save-frame" || c.name == "save-frame-displayed" || c.name == "save-scene" ||
               c.name == "save-view") {
      if (!rest.empty()) c.args = {rest};  // no path: a new numbered file next to the scene
    } else {
      std::string error;
      const std::vector<std::string> tokens = tokenize(rest, error);
      if (!error.empty()) p.fail(error);
      if (c.name == "wait-final") p.optionalNumber(tokens, "wait-final [TIMEOUT_SECONDS]");
      else if (c.name == "wait-frames") p.integers(tokens, 0, 1, "wait-frames N", 0, 1000000);
      else if (c.name == "sleep") p.numbers(tokens, 0, 1, "sleep SECONDS");
      else if (c.name == "measure-tradeoff") parseMeasureTradeoff(c, tokens, p);
      else if (c.name == "tradeoff-apply") parseTradeoffApply(c, tokens, p);
      else if (c.name == "resize") p.integers(tokens, 0, 2, "resize WIDTH HEIGHT", 64, 16384);
      else if (c.name == "quit") {
        if (tokens.size() > 1) p.fail("usage: quit [EXIT_CODE]");
        if (!tokens.empty()) p.integers(tokens, 0, 1, "quit [EXIT_CODE]", 0, 255);
      } else if (c.name == "pick") {
        p.integers(tokens, 0, 2, "pick COLUMN ROW (a pixel of the image, from its top left)", 0, 16383);
      } else if (c.name == "recovery") {
        if (tokens.size() != 1 || (tokens[0] != "restore" && tokens[0] != "discard"))
          p.fail("usage: recovery restore|discard (the unsaved edits a viewer that stopped left for this scene)");
        c.args = tokens;
      } else if (c.name == "model-up") {
        if (tokens.size() != 1 || (tokens[0] != "y" && tokens[0] != "z"))
          p.fail("usage: model-up y|z (which axis of the model on screen points up; as --up)");
        c.args = tokens;
      } else if (c.name == "view") {
        if (tokens.size() != 1 || (tokens[0] != "window" && tokens[0] != "image"))
          p.fail("usage: view window|image (the window's pixels, or the file's image)");
        c.args = tokens;
      } else if (c.name == "reload" || c.name == "print-state" || c.name == "expect-no-error" || c.name == "undo" ||
                 c.name == "redo") {
        if (!tokens.empty()) p.fail("'" + c.name + "' takes no arguments");
      } else if (c.name == "set") parseSet(c, tokens, p);
      else if (c.name == "camera") parseCamera(c, tokens, p);
      else p.fail("unknown command '" + c.name + "' (see docs/viewer.md)");
    }
    if (c.name == "sleep" && c.numbers[0] < 0) p.fail("sleep needs a time that is not negative");
    // A time beyond the limit would overflow the clock's deadline: a false timeout, or no wait at all.
    const bool timed = c.name == "sleep" || c.name == "wait-final" || c.name == "measure-tradeoff";
    if (timed && !c.numbers.empty() && c.numbers.back() > kMaxScriptSeconds)
      p.fail(c.name + ": a time of at most " + std::to_string(static_cast<long>(kMaxScriptSeconds)) + " seconds");
    if (c.name == "wait-final" && !c.numbers.empty() && c.numbers[0] <= 0) p.fail("wait-final needs a positive timeout");
    script.commands.push_back(std::move(c));
  }
  return script;
}

Script readScriptFile(const std::filesystem::path& path) {
  // As every file a user names: a FIFO or a device is refused without blocking, the size is checked first.
  const detail::UserFileRead read = detail::readUserFile(path, kMaxScriptBytes, {}, "the script");
  if (!read.problem.empty()) throw ScriptError(path.string() + ": " + read.problem);
  return parseScript(read.bytes, path.string());
}

}  // namespace rayview
