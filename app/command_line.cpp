#include "command_line.h"

#include <charconv>
#include <functional>

namespace rayview {
namespace {

enum Applies : unsigned { kRender = 1u, kView = 2u, kBoth = kRender | kView, kBench = 4u, kAll = kBoth | kBench };

struct OptionSpec {
  std::string name;
  std::string valueName;  // empty: a flag
  unsigned applies;
  std::string help;
  std::function<void(CommandLine&, const std::string& value)> apply;
};

int parseInt(const std::string& option, const std::string& text, int low, int high) {
  int value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || value < low || value > high)
    throw UsageError(option + " expects an integer from " + std::to_string(low) + " to " + std::to_string(high) +
                     ", not '" + text + "'");
  return value;
}

double parsePositive(const std::string& option, const std::string& text, double high) {
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !(value > 0.0) || value > high)
    throw UsageError(option + " expects a number above 0 and at most " + std::to_string(static_cast<int>(high)) +
                     ", not '" + text + "'");
  return value;
}

const char* modeName(unsigned mode) {
  return mode == kRender ? "'rayview render'" : (mode == kBench ? "'rayview bench'" : "the viewer");
}

// " [render]", " [render, bench]"; nothing for an option every mode takes.
std::string whereTag(unsigned applies) {
  if ((applies & kAll) == kAll) return "";
  std::string tag;
  for (auto [bit, name] : {std::pair{kRender, "render"}, std::pair{kView, "viewer"}, std::pair{kBench, "bench"}})
    if (applies & bit) tag += (tag.empty() ? "" : ", ") + std::string(name);
  return " [" + tag + "]";
}

// An option for each row of the knob table: --NAME VALUE. The bench varies the knobs it measures itself.
OptionSpec knobOption(const Knob& knob) {
  const std::string option = "--" + std::string(knob.name);
  return {option, knob.valueName(), knob.measuredByTradeoff ? kBoth : kAll, std::string(knob.help),
          [&knob, option](CommandLine& c, const std::string& v) {
            const std::optional<int> value = knob.parse(v);
            if (!value) throw UsageError(option + " expects " + knob.expectation() + ", not '" + v + "'");
            std::erase_if(c.knobs, [&](const KnobAssignment& a) { return a.knob == &knob; });
            c.knobs.push_back({&knob, *value});
          }};
}

std::vector<OptionSpec> makeOptionTable() {
  std::vector<OptionSpec> table = {
      {"-o", "OUT.png|OUT.ppm", kRender, "image to write (written whole: a temporary file renamed into place)",
       [](CommandLine& c, const std::string& v) { c.outputPath = v; }},
      {"--threads", "N", kAll, "render threads (default: one per hardware thread)",
       [](CommandLine& c, const std::string& v) { c.threads = parseInt("--threads", v, 1, 1024); }},
  };
  for (const Knob& knob : knobTable()) table.push_back(knobOption(knob));
  const std::vector<OptionSpec> rest = {
      {"--strict", "", kAll, "treat every repaired typo and unknown element as an error",
       [](CommandLine& c, const std::string&) { c.strict = true; }},
      {"--quiet", "", kRender | kBench, "print only errors",
       [](CommandLine& c, const std::string&) { c.quiet = true; }},
      {"--script", "FILE", kView, "run viewer commands from FILE (automation; see docs/viewer.md)",
       [](CommandLine& c, const std::string& v) { c.scriptPath = v; }},
      {"--out", "DIR", kBench, "directory for tradeoff.csv and the plots (created when missing)",
       [](CommandLine& c, const std::string& v) { c.outputDirectory = v; }},
      {"--scale", "F", kBench, "render at F times the camera's resolution (0 < F <= 4; default 1)",
       [](CommandLine& c, const std::string& v) { c.resolutionScale = parsePositive("--scale", v, 4.0); }},
  };
  table.insert(table.end(), rest.begin(), rest.end());
  return table;
}

const std::vector<OptionSpec>& optionTable() {
  static const std::vector<OptionSpec> table = makeOptionTable();
  return table;
}

}  // namespace

RenderSettings renderSettingsOf(const CommandLine& command) {
  RenderSettings settings;
  applyKnobs(command.knobs, {nullptr, &settings});
  return settings;
}

CommandLine parseCommandLine(const std::vector<std::string>& arguments) {
  CommandLine command;
  std::size_t i = 0;
  if (!arguments.empty() && arguments[0] == "render") {
    command.kind = CommandKind::Render;
    i = 1;
  } else if (!arguments.empty() && arguments[0] == "view") {
    i = 1;
  } else if (!arguments.empty() && arguments[0] == "bench") {
    command.kind = CommandKind::Bench;
    if (arguments.size() < 2 || arguments[1] != "tradeoff")
      throw UsageError("'rayview bench' expects a benchmark name: tradeoff");
    command.benchName = arguments[1];
    i = 2;
  }
  const unsigned mode =
      command.kind == CommandKind::Render ? kRender : (command.kind == CommandKind::Bench ? kBench : kView);
  for (; i < arguments.size(); ++i) {
    const std::string& arg = arguments[i];
    if (arg == "--help" || arg == "-h" || arg == "--version") {
      CommandLine info;
      info.kind = arg == "--version" ? CommandKind::Version : CommandKind::Help;
      return info;
    }
    if (!arg.empty() && arg[0] == '-' && arg != "-") {
      std::string name = arg, value;
      bool hasInlineValue = false;
      if (const auto eq = arg.find('='); eq != std::string::npos && arg.rfind("--", 0) == 0) {
        name = arg.substr(0, eq);
        value = arg.substr(eq + 1);
        hasInlineValue = true;
      }
      const OptionSpec* spec = nullptr;
      for (const OptionSpec& s : optionTable())
        if (name == s.name) spec = &s;
      if (!spec) throw UsageError("unknown option '" + name + "' (see rayview --help)");
      if (!(spec->applies & mode))
        throw UsageError("option '" + name + "' does not apply to " + modeName(mode));
      if (!spec->valueName.empty() && !hasInlineValue) {
        if (i + 1 >= arguments.size()) throw UsageError("option '" + name + "' expects " + spec->valueName);
        value = arguments[++i];
      } else if (spec->valueName.empty() && hasInlineValue) {
        throw UsageError("option '" + name + "' takes no value");
      }
      spec->apply(command, value);
      continue;
    }
    if (command.kind == CommandKind::Bench) {
      command.scenePaths.push_back(arg);
      continue;
    }
    if (!command.scenePath.empty()) throw UsageError("more than one scene given: '" + command.scenePath + "' and '" + arg + "'");
    command.scenePath = arg;
  }
  if (command.kind == CommandKind::Render) {
    if (command.outputPath.empty()) throw UsageError("'rayview render' needs -o OUT.png or -o OUT.ppm");
  }
  if (command.kind == CommandKind::Bench) {
    if (command.scenePaths.empty()) throw UsageError("'rayview bench tradeoff' needs at least one SCENE");
    if (command.outputDirectory.empty()) throw UsageError("'rayview bench tradeoff' needs --out DIR");
  }
  return command;
}

std::string helpText() {
  std::string text =
      "rayview: a Whitted ray tracer for the CSE 461 scene format\n"
      "\n"
      "usage:\n"
      "  rayview [SCENE] [options]               open the viewer (the embedded default scene without SCENE)\n"
      "  rayview render [SCENE] -o OUT [options] render headless to PNG or PPM and print timings\n"
      "  rayview bench tradeoff SCENE... --out DIR [options]\n"
      "                                          time and error of every knob setting: DIR/tradeoff.csv and\n"
      "                                          DIR/<scene>_tradeoff.png (see docs/tradeoff.md)\n"
      "  rayview --help | --version\n"
      "\n"
      "options:\n";
  for (const OptionSpec& s : optionTable()) {
    std::string left = "  " + s.name + (s.valueName.empty() ? "" : " " + s.valueName);
    if (left.size() < 32) left.resize(32, ' ');
    else left += "  ";
    text += left + s.help + whereTag(s.applies) + "\n";
  }
  text +=
      "\n"
      "exit status: 0 success, 1 the output could not be written, 2 bad scene or bad arguments (nothing written)\n";
  return text;
}

std::string versionText() {
  std::string text = std::string("rayview ") + RAYVIEW_VERSION;
#ifdef RAYVIEW_HAVE_EMBREE
  text += " (Embree 3 traversal and the reference BVH)";
#else
  text += " (reference BVH only: built without Embree)";
#endif
  return text + "\n";
}

}  // namespace rayview
