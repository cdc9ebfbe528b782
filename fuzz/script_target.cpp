// Fuzz target "script": the viewer's automation-script parser (ui/automation_script.cpp, compiled in alone so
// no GL is linked). Any text either parses or throws ScriptError with "FILE:LINE: message"; what parses is
// what the runner may rely on (finite numbers, a line number, a name).
#include <cmath>
#include <string>

#include "automation_script.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace rayview;
  const std::string text(fuzz::asText(data, size));
  try {
    const Script script = parseScript(text, "fuzz.script");
    for (const ScriptCommand& c : script.commands) {
      if (c.line <= 0) fuzz::fail("a command without a line number");
      if (c.name.empty()) fuzz::fail("a command without a name");
      for (const double v : c.numbers)
        if (!std::isfinite(v)) fuzz::fail("a non-finite number passed the parser");
    }
  } catch (const ScriptError& error) {
    if (std::string(error.what()).rfind("fuzz.script:", 0) != 0) fuzz::fail("a ScriptError not located as FILE:LINE");
  }
  return 0;
}
