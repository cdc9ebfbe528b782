#include "command_line.h"

#include "rayview/build_features.h"

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <filesystem>
#include <functional>

#include "rayview/lean_memory.h"

namespace rayview {
namespace {

// Which commands take an option. kAll: every command that renders (compare takes only its own).
enum Applies : unsigned {
  kRender = 1u,
  kView = 2u,
  kBoth = kRender | kView,
  kBench = 4u,
  kAll = kBoth | kBench,
  kCompare = 8u,
  kImport = 16u,
  kExport = 32u,
  // Every command that opens a scene: they all take the options of how to open it (rayview/scene_open.h).
  kOpen = kAll | kImport | kExport
};

struct Subcommand {
  const char* name;
  CommandKind kind;
  unsigned mode;
};
constexpr Subcommand kSubcommands[] = {{"render", CommandKind::Render, kRender},
                                       {"view", CommandKind::View, kView},
                                       {"bench", CommandKind::Bench, kBench},
                                       {"compare", CommandKind::Compare, kCompare},
                                       {"import", CommandKind::Import, kImport},
                                       {"export", CommandKind::Export, kExport}};

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
  if (mode == kCompare) return "'rayview compare'";
  if (mode == kImport || mode == kExport) return mode == kImport ? "'rayview import'" : "'rayview export'";
  return mode == kRender ? "'rayview render'" : (mode == kBench ? "'rayview bench'" : "the viewer");
}

double parsePercent(const std::string& option, const std::string& text) {
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !(value >= 0.0 && value <= 100.0))
    throw UsageError(option + " expects a percentage from 0 to 100, not '" + text + "'");
  return value;
}

std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// A first argument that is no existing file and reads like a word ("rendr"), not like a path ("scene.xml").
bool looksLikeCommand(const std::string& arg) {
  if (arg.empty() || !(arg[0] >= 'a' && arg[0] <= 'z') || std::filesystem::exists(arg)) return false;
  return std::all_of(arg.begin(), arg.end(), [](char c) { return (c >= 'a' && c <= 'z') || c == '-'; });
}

[[noreturn]] void unknownCommand(const std::string& word) {
  const Subcommand* nearest = nullptr;
  std::size_t best = 3;  // at most two edits away
  for (const Subcommand& sub : kSubcommands)
    if (const std::size_t d = editDistance(word, sub.name); d < best) {
      best = d;
      nearest = &sub;
    }
  if (nearest) throw UsageError("unknown command '" + word + "' (did you mean '" + nearest->name + "'?)");
  throw UsageError("unknown command '" + word +
                   "' (commands: render, bench, compare, import, export, view; or the path of a scene file, see rayview --help)");
}

// " [render]", " [render, bench]"; nothing for an option every mode takes.
std::string whereTag(unsigned applies) {
  if ((applies & kAll) == kAll) return "";
  std::string tag;
  for (auto [bit, name] : {std::pair{kRender, "render"}, std::pair{kView, "viewer"}, std::pair{kBench, "bench"},
                          std::pair{kImport, "import"}, std::pair{kExport, "export"}})
    if (applies & bit) tag += (tag.empty() ? "" : ", ") + std::string(name);
  return " [" + tag + "]";
}

// An option for each row of the knob table: --NAME VALUE. The bench varies the knobs it measures itself.
OptionSpec knobOption(const Knob& knob) {
  const std::string option = "--" + std::string(knob.name);
  return {option, knob.valueName(), knob.measuredByTradeoff() ? kBoth : kAll,
          std::string(knob.help) + " (default: " + knob.defaultText() + ")",
          [&knob, option](CommandLine& c, const std::string& v) {
            const std::optional<int> value = knob.parse(v);
            if (!value) throw UsageError(option + " expects " + knob.expectation() + ", not '" + v + "'");
            std::erase_if(c.job.knobs, [&](const KnobAssignment& a) { return a.knob == &knob; });
            c.job.knobs.push_back({&knob, *value});
          }};
}

std::vector<OptionSpec> makeOptionTable() {
  std::vector<OptionSpec> table = {
      {"-o", "OUT.png|OUT.ppm", kRender | kImport | kExport,
       "image to write (written whole: a temporary file renamed into place); import: SCENE.xml; export: the model",
       [](CommandLine& c, const std::string& v) { c.job.output = v; }},
      {"--up", "y|z", kOpen, "a model's up axis, for the camera made up for it (z for CAD and scans)",
       [](CommandLine& c, const std::string& v) {
         if (!parseModelUpAxis(v, c.job.open.model.up)) throw UsageError("--up expects y or z, not '" + v + "'");
       }},
      {"--resolution", "WxH", kOpen, "a model's image size (default 1280x720)",
       [](CommandLine& c, const std::string& v) {
         if (!parseResolution(v, c.job.open.model.width, c.job.open.model.height))
           throw UsageError("--resolution expects WIDTHxHEIGHT up to 32768x32768, not '" + v + "'");
       }},
      {"--threads", "N", kAll, "threads that load and render (default: one per hardware thread)",
       [](CommandLine& c, const std::string& v) { c.job.threads = parseInt("--threads", v, 1, 1024); }},
  };
  for (const Knob& knob : knobTable()) table.push_back(knobOption(knob));
  const std::vector<OptionSpec> rest = {
      {"--strict", "", kOpen, "treat every repaired typo and unknown element as an error",
       [](CommandLine& c, const std::string&) { c.job.open.strict = true; }},
      {"--memory", "auto|fast|lean", kRender,
       "fast: Embree and the whole image; lean: less memory, slower (the packet BVH with bigger leaves, the image "
       "deflated while the scene is held); auto: lean only when the fast layout's estimated peak would not fit in "
       "the available memory (default: auto)",
       [](CommandLine& c, const std::string& v) {
         if (!parseMemoryUse(v, c.job.open.memory)) throw UsageError("--memory expects 'auto', 'fast' or 'lean', not '" + v + "'");
       }},
      {"--camera", "N|file|auto", kOpen,
       "which camera to open: of a CENG477 scene's <Cameras>, N (1 is the first, the default; render -o DIR/ writes "
       "every camera to its <ImageName> unless one is chosen); of a model, the file's own (file) or rayview's "
       "framing (auto) instead of the default: the file's when it shows the model",
       [](CommandLine& c, const std::string& v) {
         if (parseModelCamera(v, c.job.open.model.camera)) return;  // a word for a model, else a camera number
         c.job.open.camera = parseInt("--camera", v, 1, 1000000);
       }},
      {"--lights", "file|kit", kOpen,
       "a model's lights: the file's own (file) or rayview's key/fill/back kit (kit) instead of the default: the "
       "file's when they light the model",
       [](CommandLine& c, const std::string& v) {
         if (!parseModelLights(v, c.job.open.model.lights)) throw UsageError("--lights expects file or kit, not '" + v + "'");
       }},
      {"--copy-textures", "", kImport,
       "copy a texture that lies outside the model's folder beside the scene too (by default the scene names it "
       "where it lies); one inside the folder is always copied",
       [](CommandLine& c, const std::string&) { c.copyTextures = true; }},
      {"--turntable", "N", kRender,
       "render N frames orbiting the camera around the scene's centre (the viewer's orbit pivot); -o names them "
       "with a printf number, e.g. -o frames/spin_%04d.png",
       [](CommandLine& c, const std::string& v) { c.job.turntableFrames = parseInt("--turntable", v, 1, 100000); }},
      {"--overwrite", "", kRender, "with several frames or scenes: render them all, not only those whose file is missing or incomplete",
       [](CommandLine& c, const std::string&) { c.job.overwrite = true; }},
      {"--quiet", "", kRender | kBench, "print only errors",
       [](CommandLine& c, const std::string&) { c.job.quiet = true; }},
      {"--script", "FILE", kView, "run viewer commands from FILE (automation; see docs/viewer.md)",
       [](CommandLine& c, const std::string& v) { c.scriptPath = v; }},
      {"--compare", "REF.png|REF.ppm", kView,
       "compare the render with a reference image of its size: the Compare panel's figures, hold Space to see the "
       "reference, D for the difference (see docs/viewer.md)",
       [](CommandLine& c, const std::string& v) { c.comparePath = v; }},
      {"--out", "DIR", kBench, "directory for tradeoff.csv and the plots (created when missing)",
       [](CommandLine& c, const std::string& v) { c.outputDirectory = v; }},
      {"--scale", "F", kBench, "render at F times the camera's resolution (0 < F <= 4; default 1)",
       [](CommandLine& c, const std::string& v) { c.resolutionScale = parsePositive("--scale", v, 4.0); }},
      {"--diff", "OUT.png", kCompare, "write a false-colour map of the differences (see docs/viewer.md)",
       [](CommandLine& c, const std::string& v) { c.diffPath = v; }},
      {"--min-within1", "P", kCompare,
       "exit 1 unless at least P% of the pixels are within 1 of the reference in every channel (default 100)",
       [](CommandLine& c, const std::string& v) { c.minWithin1 = parsePercent("--min-within1", v); }},
  };
  table.insert(table.end(), rest.begin(), rest.end());
  return table;
}

const std::vector<OptionSpec>& optionTable() {
  static const std::vector<OptionSpec> table = makeOptionTable();
  return table;
}

// The option at arguments[i] (and its value, which may be the next argument: i moves past it) applied to `command`.
void applyOption(const std::vector<std::string>& arguments, std::size_t& i, unsigned mode, CommandLine& command) {
  const std::string& arg = arguments[i];
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
  if (!spec) {
    const std::string help = mode == kView ? "rayview --help" : "rayview " + arguments[0] + " --help";
    throw UsageError("unknown option '" + name + "' (see " + help + ")");
  }
  if (!(spec->applies & mode)) throw UsageError("option '" + name + "' does not apply to " + modeName(mode));
  if (!spec->valueName.empty() && !hasInlineValue) {
    if (i + 1 >= arguments.size()) throw UsageError("option '" + name + "' expects " + spec->valueName);
    value = arguments[++i];
  } else if (spec->valueName.empty() && hasInlineValue) {
    throw UsageError("option '" + name + "' takes no value");
  }
  spec->apply(command, value);
}

// What each command cannot do without.
void checkRequiredArguments(const CommandLine& command) {
  if (command.kind == CommandKind::Render) {
    if (command.job.output.empty()) throw UsageError("'rayview render' needs -o OUT.png or -o OUT.ppm");
  }
  const bool noInput = command.job.scenes.empty(), noOutput = command.job.output.empty();
  if (command.kind == CommandKind::Import && (noInput || noOutput))
    throw UsageError("'rayview import' needs MODEL -o SCENE.xml");
  if (command.kind == CommandKind::Export && (noInput || noOutput))
    throw UsageError("'rayview export' needs SCENE -o MODEL.obj|.ply|.stl|.gltf|.glb");
  if (command.kind == CommandKind::Bench) {
    if (noInput) throw UsageError("'rayview bench tradeoff' needs at least one SCENE");
    if (command.outputDirectory.empty()) throw UsageError("'rayview bench tradeoff' needs --out DIR");
  }
  if (command.kind == CommandKind::Compare && command.images.size() != 2)
    throw UsageError("'rayview compare' needs two images: IMAGE REFERENCE (" +
                     std::to_string(command.images.size()) + " given)");
}

}  // namespace

CommandLine parseCommandLine(const std::vector<std::string>& arguments) {
  CommandLine command;
  std::size_t i = 0;
  if (!arguments.empty()) {
    for (const Subcommand& sub : kSubcommands)
      if (arguments[0] == sub.name) {
        command.kind = sub.kind;
        i = 1;
      }
    if (i == 0 && looksLikeCommand(arguments[0])) unknownCommand(arguments[0]);
  }
  if (command.kind == CommandKind::Bench) {
    const bool wantsHelp = arguments.size() >= 2 && (arguments[1] == "--help" || arguments[1] == "-h");
    if (!wantsHelp && (arguments.size() < 2 || arguments[1] != "tradeoff"))
      throw UsageError("'rayview bench' expects a benchmark name: tradeoff");
    if (!wantsHelp) {
      command.benchName = arguments[1];
      i = 2;
    }
  }
  unsigned mode = kView;
  for (const Subcommand& sub : kSubcommands)
    if (sub.kind == command.kind) mode = sub.mode;
  for (; i < arguments.size(); ++i) {
    const std::string& arg = arguments[i];
    if (arg == "--help" || arg == "-h" || arg == "--version") {
      CommandLine info;
      info.kind = arg == "--version" ? CommandKind::Version : CommandKind::Help;
      info.helpFor = command.kind;
      return info;
    }
    if (!arg.empty() && arg[0] == '-' && arg != "-") {
      applyOption(arguments, i, mode, command);
      continue;
    }
    if (command.kind == CommandKind::Compare) {
      command.images.push_back(arg);  // the image, then the reference
      continue;
    }
    // render and bench take several (render: a batch into a directory); the others one.
    std::vector<std::string>& scenes = command.job.scenes;
    if (!scenes.empty() && command.kind != CommandKind::Render && command.kind != CommandKind::Bench)
      throw UsageError("more than one scene given: '" + scenes.front() + "' and '" + arg + "'");
    scenes.push_back(arg);
  }
  checkRequiredArguments(command);
  return command;
}

namespace {

std::string optionLines(unsigned mode) {
  std::string text;
  for (const OptionSpec& s : optionTable()) {
    if (mode != kView && !(s.applies & mode)) continue;
    if (mode == kView && s.applies == kCompare) continue;  // the global help lists compare's in its own help
    std::string left = "  " + s.name + (s.valueName.empty() ? "" : " " + s.valueName);
    if (left.size() < 32) left.resize(32, ' ');
    else left += "  ";
    text += left + s.help + (mode == kView ? whereTag(s.applies) : std::string()) + "\n";
  }
  return text;
}

// `rayview import` and `rayview export`: between a scene and the formats other tools read.
std::string modelCommandHelp(CommandKind kind) {
  switch (kind) {
    case CommandKind::Import:
      return "usage: rayview import MODEL -o SCENE.xml [--up y|z] [--resolution WxH]\n"
             "\n"
             "Writes MODEL (OBJ, PLY, STL, glTF/GLB and the other formats Assimp reads) as a scene in the handout's\n"
             "format, with a camera, lights and materials made up for what it lacks and its texture as a PNG beside\n"
             "it; prints one summary line (see docs/scene-format.md, \"Opening models\").\n"
             "\n"
             "options:\n" +
             optionLines(kImport) + "\nexit status: 0 success, 1 the output could not be written, 2 bad model or bad arguments\n";
    case CommandKind::Export:
      return "usage: rayview export SCENE -o MODEL.obj|.ply|.stl|.gltf|.glb\n"
             "\n"
             "Writes the geometry and materials of any input (a scene, a CENG477 file's camera, a model) for other\n"
             "tools.\n"
             "\n"
             "options:\n" +
             optionLines(kExport) + "\nexit status: 0 success, 2 bad scene, bad arguments or the model could not be written\n";
    default:
      return {};
  }
}

}  // namespace

std::string helpText(CommandKind kind) {
  switch (kind) {
    case CommandKind::Render:
      return "usage: rayview render [SCENE] -o OUT.png|OUT.ppm [options]\n"
             "       rayview render SCENE --turntable N -o DIR/NAME_%04d.png [options]\n"
             "       rayview render SCENE... -o DIR/ [options]\n"
             "\n"
             "Renders SCENE (the embedded default scene without it) headless and prints timings. Frames of a turntable or\n"
             "a batch of scenes whose file is already complete are not rendered again (--overwrite renders them).\n"
             "Under mpirun, the ranks share the work (docs/scale-out.md).\n"
             "\n"
             "options:\n" +
             optionLines(kRender) +
             "\nexit status: 0 success, 1 the output could not be written, 2 bad scene or bad arguments (nothing "
             "written), 3 out of memory\n";
    case CommandKind::Bench:
      return "usage: rayview bench tradeoff SCENE... --out DIR [options]\n"
             "\n"
             "Time and error of every knob setting: DIR/tradeoff.csv and DIR/<scene>_tradeoff.png (see "
             "docs/tradeoff.md).\n"
             "\n"
             "options:\n" +
             optionLines(kBench);
    case CommandKind::Compare:
      return "usage: rayview compare IMAGE REFERENCE [--diff OUT.png] [--min-within1 P]\n"
             "\n"
             "Compares two images of the same size (PNG or PPM) and prints\n"
             "  exact=E% within1=W% maxdiff=M psnr=P\n"
             "(% of pixels identical, % within 1 in every channel, the largest channel difference, PSNR in dB).\n"
             "\n"
             "options:\n" +
             optionLines(kCompare) +
             "\nexit status: 0 within the threshold, 1 not, 2 bad arguments, an unreadable image or different sizes, 3 "
             "out of memory\n";
    case CommandKind::Import:
    case CommandKind::Export:
      return modelCommandHelp(kind);
    default:
      break;
  }
  std::string text =
      "rayview: a Whitted ray tracer for the CSE 461 scene format\n"
      "\n"
      "usage:\n"
      "  rayview [SCENE] [options]               open the viewer (the embedded default scene without SCENE)\n"
      "  rayview render [SCENE] -o OUT [options] render headless to PNG or PPM and print timings\n"
      "  rayview bench tradeoff SCENE... --out DIR [options]\n"
      "                                          time and error of every knob setting: DIR/tradeoff.csv and\n"
      "                                          DIR/<scene>_tradeoff.png (see docs/tradeoff.md)\n"
      "  rayview compare IMAGE REFERENCE [--diff OUT.png] [--min-within1 P]\n"
      "                                          how far IMAGE is from REFERENCE\n"
      "  rayview import MODEL -o SCENE.xml       a model (OBJ, PLY, STL, glTF...) as a scene in this format\n"
      "  rayview export SCENE.xml -o MODEL.obj|.ply|.stl|.gltf|.glb\n"
      "                                          the scene's geometry and materials for other tools\n"
      "  (SCENE may be the handout's XML, a CENG477 file or a model file, in every command: see\n"
      "   docs/inputs-and-options.md)\n"
      "  rayview COMMAND --help                  a command's own usage and options\n"
      "  rayview --help | --version\n"
      "\n"
      "options:\n";
  text += optionLines(kView);
  text +=
      "\n"
      "exit status: 0 success, 1 the output could not be written, 2 bad scene or bad arguments (nothing written), 3 "
      "out of memory\n";
  return text;
}

std::string versionText() {
  std::string text = std::string("rayview ") + RAYVIEW_VERSION;
#if defined(RAYVIEW_HAVE_EMBREE) && defined(RAYVIEW_EMBREE_LINKED)
  text += " (Embree 3 traversal, linked; rayview's packet BVH; the reference BVH)";
#elif defined(RAYVIEW_HAVE_EMBREE)
  text += " (Embree 3 traversal, loaded when a scene needs it; rayview's packet BVH; the reference BVH)";
#else
  text += " (built without Embree: rayview's packet BVH in its place; the reference BVH)";
#endif
  return text + "\n";
}

}  // namespace rayview
