#pragma once
// A pre-pass over the raw text that repairs the handout's malformed tags before tinyxml2 sees them
// (SPEC section 2). It never adds or removes a newline, so every line number stays that of the file.

#include <string>
#include <string_view>
#include <vector>

#include "rayview/diagnostics.h"

namespace rayview::detail {

struct RepairedXml {
  std::string text;                 // the repaired text; empty when `changed` is false (use the input)
  bool changed = false;
  std::vector<Diagnostic> repairs;  // one located warning per repair
};

// Repairs:
//  - a closing tag clearly meant for the open element (a known alias or a small misspelling) is
//    renamed to match it;
//  - a closing tag that names nothing open is dropped (blanked out);
//  - a leaf element left open right before its parent's closing tag is closed there.
// Throws SceneError (located) for a truncated file, an unterminated tag or comment, or a closing tag
// that cannot be matched safely. In strict mode the first repair is thrown as an error instead.
RepairedXml repairXml(std::string_view text, const std::string& displayName, bool strict);

// The canonical (lowercase) spelling of an element name when `name` is an accepted alias
// ("intesity" -> "intensity"), else empty.
std::string_view canonicalAlias(std::string_view lowercaseName);

// Case-insensitive ASCII comparison.
bool equalsIgnoreCase(std::string_view a, std::string_view b);

}  // namespace rayview::detail
