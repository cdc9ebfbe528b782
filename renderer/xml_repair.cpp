#include "xml_repair.h"

#include <algorithm>
#include <cstring>
#include <string_view>

namespace rayview::detail {

namespace {

constexpr std::string_view kAliases[][2] = {
    {"backgroundcolor", "background"},
    {"intesity", "intensity"},
    {"traingularlight", "triangularlight"},
    {"mirrorreflactance", "mirrorreflectance"},
};

char lower(char c) { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c; }

std::string toLower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = lower(c);
  return out;
}

std::string canonical(std::string_view name) {
  std::string l = toLower(name);
  std::string_view alias = canonicalAlias(l);
  return alias.empty() ? l : std::string(alias);
}

// Optimal-string-alignment distance (a transposition counts as one edit): "ambinet" is 1 from "ambient".
std::size_t editDistance(std::string_view a, std::string_view b) {
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::size_t> prev2(m + 1), prev(m + 1), cur(m + 1);
  for (std::size_t j = 0; j <= m; ++j) prev[j] = j;
  for (std::size_t i = 1; i <= n; ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= m; ++j) {
      std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) cur[j] = std::min(cur[j], prev2[j - 2] + 1);
    }
    std::swap(prev2, prev);
    std::swap(prev, cur);
  }
  return prev[m];
}

// How many edits still count as "clearly a misspelling" of a name this long. Short names get none:
// </up> is never read as </gaze>.
std::size_t allowedEdits(std::size_t length) {
  if (length <= 4) return 0;
  if (length <= 8) return 1;
  if (length <= 12) return 2;
  return 3;
}

// Is the closing name `closing` clearly meant for the open element `open`?
bool meantFor(std::string_view closing, std::string_view open) {
  const std::string c = toLower(closing);
  const std::string canon = canonical(open);
  if (canonical(closing) == canon) return true;
  // Element names of the format are short; a long name is no misspelling (and keeps the distance cheap).
  constexpr std::size_t kLongestName = 64;
  if (closing.size() > kLongestName || open.size() > kLongestName) return false;
  std::vector<std::string> spellings{toLower(open), canon};
  for (const auto& alias : kAliases)
    if (alias[1] == canon) spellings.emplace_back(alias[0]);
  for (const std::string& s : spellings)
    if (editDistance(c, s) <= allowedEdits(s.size())) return true;
  return false;
}

bool isNameStart(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' || c == ':' || static_cast<unsigned char>(c) >= 0x80;
}
bool isNameChar(char c) { return isNameStart(c) || (c >= '0' && c <= '9') || c == '-' || c == '.'; }
bool isSpace(char c) { return c == ' ' || c == '\n' || c == '\t' || c == '\r'; }

// "<name>" or "</name>", built with append: GCC 12 warns (-Wrestrict, a false positive) on "<" + std::string.
std::string tag(std::string_view name, bool closing) {
  std::string s(closing ? "</" : "<");
  s.append(name);
  s.push_back('>');
  return s;
}

struct OpenElement {
  std::string_view name;
  int line = 0;
  bool hasChildren = false;
  std::string canonicalName;  // computed once, compared for every closing tag below it
};

// The deepest nesting accepted: tinyxml2's own limit (TINYXML2_MAX_ELEMENT_DEPTH), which refuses
// anything deeper anyway; the format itself nests 4 deep. Every closing tag looks at the open elements,
// so this bound is what keeps the pass linear in the file size (without it, 20 000 nested elements with
// misspelled closing tags took 6 s, 200 000 did not finish in minutes).
constexpr std::size_t kMaxNesting = 100;

class Repairer {
 public:
  Repairer(std::string_view text, const std::string& file, bool strict) : text_(text), file_(file), strict_(strict) {}

  RepairedXml run() {
    const std::size_t n = text_.size();
    std::size_t i = text_.substr(0, 3) == "\xEF\xBB\xBF" ? 3 : 0;  // a UTF-8 byte order mark
    while (true) {
      const void* hit = i < n ? std::memchr(text_.data() + i, '<', n - i) : nullptr;
      const std::size_t next = hit ? static_cast<std::size_t>(static_cast<const char*>(hit) - text_.data()) : n;
      if (stack_.empty()) outsideText(i, next);
      if (!hit) break;
      i = token(next);
    }
    if (!stack_.empty()) {
      const OpenElement& open = stack_.back();
      fail(lineAt(n), "the file ends before <" + std::string(open.name) + "> (opened at line " +
                          std::to_string(open.line) + ") is closed; the file looks truncated");
    }
    if (result_.changed) result_.text.append(text_.substr(copied_));
    return std::move(result_);
  }

 private:
  // Handles the markup starting at `i` (text_[i] == '<'); returns the offset just after it.
  std::size_t token(std::size_t i) {
    const std::size_t n = text_.size();
    auto startsWith = [&](std::string_view s) { return text_.compare(i, s.size(), s) == 0; };
    auto skipTo = [&](std::string_view terminator, const char* what) {
      std::size_t end = text_.find(terminator, i);
      if (end == std::string_view::npos)
        fail(lineAt(i), std::string("the file ends inside the ") + what + " that starts here; the file looks truncated");
      return end + terminator.size();
    };
    if (startsWith("<!--")) return skipTo("-->", "comment");
    if (startsWith("<![CDATA[")) return skipTo("]]>", "CDATA section");
    if (startsWith("<?")) return skipTo("?>", "<?...?> declaration");
    if (startsWith("<!")) return skipTo(">", "<!...> declaration");
    if (startsWith("</")) return closingTag(i);
    if (i + 1 < n && isNameStart(text_[i + 1])) return openingTag(i);
    fail(lineAt(i), "'<' is not followed by an element name (a literal '<' must be written &lt;)");
  }

  std::size_t openingTag(std::size_t i) {
    const std::size_t n = text_.size();
    std::size_t j = i + 1;
    while (j < n && isNameChar(text_[j])) ++j;
    std::string_view name = text_.substr(i + 1, j - i - 1);
    char quote = 0;
    for (; j < n; ++j) {
      char c = text_[j];
      if (quote) {
        if (c == quote) quote = 0;
      } else if (c == '"' || c == '\'') {
        quote = c;
      } else if (c == '<') {
        fail(lineAt(i), "the tag <" + std::string(name) + " is not closed with '>'");
      } else if (c == '>') {
        break;
      }
    }
    if (j >= n)
      fail(lineAt(i), "the file ends inside the tag <" + std::string(name) + "; the file looks truncated");
    const bool selfClosing = text_[j - 1] == '/';
    if (!stack_.empty()) stack_.back().hasChildren = true;
    if (!selfClosing) {
      if (stack_.size() >= kMaxNesting)
        fail(lineAt(i), "XML syntax error: elements nested too deeply (<" + std::string(name) + "> is " +
                            std::to_string(kMaxNesting + 1) + " levels deep; the limit is " +
                            std::to_string(kMaxNesting) + ")");
      stack_.push_back({name, lineAt(i), false, canonical(name)});
    }
    return j + 1;
  }

  std::size_t closingTag(std::size_t i) {
    const std::size_t n = text_.size();
    std::size_t nameBegin = i + 2, j = nameBegin;
    while (j < n && isNameChar(text_[j])) ++j;
    const std::size_t nameEnd = j;
    while (j < n && isSpace(text_[j])) ++j;
    if (j >= n) fail(lineAt(i), "the file ends inside a closing tag; the file looks truncated");
    const std::string_view name = text_.substr(nameBegin, nameEnd - nameBegin);
    if (name.empty() || text_[j] != '>')
      fail(lineAt(i), "malformed closing tag '" + std::string(text_.substr(i, std::min<std::size_t>(j - i + 1, 40))) + "'");
    const std::size_t end = j + 1;
    const std::string c = tag(name, true);

    if (stack_.empty()) {
      repair(lineAt(i), "stray closing tag " + c + " dropped (there is no open element to close)");
      blank(i, end);
      return end;
    }
    const OpenElement& top = stack_.back();
    const std::string t = tag(top.name, false);
    if (equalsIgnoreCase(name, top.name)) {
      // Names are case-insensitive in this format but not in XML: make the case match, silently.
      if (name != top.name) replace(nameBegin, nameEnd, top.name);
      stack_.pop_back();
      return end;
    }
    // The closing name is exactly an outer open element: the inner one was left open.
    std::size_t outer = stack_.size();
    const std::string closingCanonical = canonical(name);
    for (std::size_t k = stack_.size() - 1; k-- > 0;)
      if (closingCanonical == stack_[k].canonicalName) {
        outer = k;
        break;
      }
    if (outer == stack_.size() && meantFor(name, top.name)) {
      repair(lineAt(i), "closing tag " + c + " read as </" + std::string(top.name) + "> (it closes " + t +
                            " opened at line " + std::to_string(top.line) + ")");
      replace(nameBegin, nameEnd, top.name);
      stack_.pop_back();
      return end;
    }
    if (outer != stack_.size()) {
      if (outer + 2 == stack_.size() && !top.hasChildren) {
        repair(lineAt(i), t + " opened at line " + std::to_string(top.line) + " is not closed; closed before " + c);
        replace(i, i, tag(top.name, true));
        stack_.pop_back();
        if (name != stack_.back().name) replace(nameBegin, nameEnd, stack_.back().name);
        stack_.pop_back();
        return end;
      }
      fail(lineAt(i), c + " closes <" + std::string(stack_[outer].name) + "> opened at line " +
                          std::to_string(stack_[outer].line) + ", but " + t + " opened at line " +
                          std::to_string(top.line) + " is still open");
    }
    for (std::size_t k = 0; k + 1 < stack_.size(); ++k)
      if (meantFor(name, stack_[k].name))
        fail(lineAt(i), "closing tag " + c + " does not match " + t + " opened at line " +
                            std::to_string(top.line));
    repair(lineAt(i), "stray closing tag " + c + " dropped (no open element of that name; " + t +
                          " opened at line " + std::to_string(top.line) + " is still open)");
    blank(i, end);
    return end;
  }

  // Text outside the root element is not XML (tinyxml2 would refuse it): drop it, as the walker ignores
  // stray text inside elements.
  void outsideText(std::size_t begin, std::size_t end) {
    std::size_t b = begin;
    while (b < end && isSpace(text_[b])) ++b;
    if (b == end) return;
    std::size_t e = end;
    while (e > b && isSpace(text_[e - 1])) --e;
    std::string shown(text_.substr(b, std::min<std::size_t>(e - b, 32)));
    if (e - b > 32) shown += "...";
    repair(lineAt(b), "stray text '" + shown + "' ignored");
    blank(begin, end);
  }

  // --- output: copy the input lazily, only once something changes ---
  void replace(std::size_t begin, std::size_t end, std::string_view with) {
    result_.changed = true;
    result_.text.reserve(text_.size() + 64);
    result_.text.append(text_.substr(copied_, begin - copied_));
    result_.text.append(with);
    copied_ = end;
  }
  void blank(std::size_t begin, std::size_t end) {
    std::string spaces(text_.substr(begin, end - begin));
    for (char& ch : spaces)
      if (ch != '\n' && ch != '\r') ch = ' ';
    replace(begin, end, spaces);
  }

  void repair(int line, const std::string& message) {
    if (strict_) fail(line, message + " [strict mode]");
    result_.repairs.push_back(Diagnostic{Severity::Warning, {file_, line}, message});
  }
  [[noreturn]] void fail(int line, const std::string& message) { throwSceneError({file_, line}, message); }

  // 1-based line of an offset. Offsets only grow, so a cursor makes the whole pass one count.
  int lineAt(std::size_t offset) {
    offset = std::min(offset, text_.size());
    if (offset < lineOffset_) return static_cast<int>(1 + std::count(text_.begin(), text_.begin() + static_cast<std::ptrdiff_t>(offset), '\n'));
    line_ += static_cast<int>(std::count(text_.begin() + static_cast<std::ptrdiff_t>(lineOffset_),
                                         text_.begin() + static_cast<std::ptrdiff_t>(offset), '\n'));
    lineOffset_ = offset;
    return line_;
  }

  std::string_view text_;
  const std::string& file_;
  bool strict_;
  std::vector<OpenElement> stack_;
  RepairedXml result_;
  std::size_t copied_ = 0;
  std::size_t lineOffset_ = 0;
  int line_ = 1;
};

}  // namespace

std::string_view canonicalAlias(std::string_view lowercaseName) {
  for (const auto& alias : kAliases)
    if (alias[0] == lowercaseName) return alias[1];
  return {};
}

bool equalsIgnoreCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (lower(a[i]) != lower(b[i])) return false;
  return true;
}

RepairedXml repairXml(std::string_view text, const std::string& displayName, bool strict) {
  return Repairer(text, displayName, strict).run();
}

}  // namespace rayview::detail
