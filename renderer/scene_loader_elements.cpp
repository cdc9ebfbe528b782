// The scene loader's tolerant element readers: located messages, element names (case, aliases),
// the numbers and text inside an element. The walk (scene_loader_walk.cpp) calls these for every element.

#include <cctype>
#include <cstdio>

#include "scene_loader_internal.h"

namespace rayview::scene_loading {

void WarningList::add(Diagnostic diagnostic) {
  auto [it, inserted] = index_.emplace(diagnostic.message, entries_.size());
  if (inserted) entries_.push_back({std::move(diagnostic), 1});
  else ++entries_[it->second].count;
}

std::vector<Diagnostic> WarningList::take() {
  std::vector<Diagnostic> out;
  out.reserve(entries_.size());
  for (Entry& entry : entries_) {
    if (entry.count > 1) entry.diagnostic.message += " (" + std::to_string(entry.count) + " times; the first is shown)";
    out.push_back(std::move(entry.diagnostic));
  }
  entries_.clear();
  index_.clear();
  std::stable_sort(out.begin(), out.end(),
                   [](const Diagnostic& a, const Diagnostic& b) { return a.where.line < b.where.line; });
  return out;
}

// Warnings with the same text are reported once, at the first line, with a count.
void Loader::warn(int line, const std::string& message) {
  warnings_.add(Diagnostic{Severity::Warning, {file_, line}, message});
}

// Something the format does not allow but that we can read anyway: an error in strict mode.
void Loader::nonconforming(int line, const std::string& message) {
  if (options_.strict) fail(line, message + " [strict mode]");
  warn(line, message);
}

void Loader::xmlError(const tinyxml2::XMLDocument& doc, std::string_view text) {
  std::string what;
  switch (doc.ErrorID()) {
    case tinyxml2::XML_ERROR_EMPTY_DOCUMENT: {
      // No element: either nothing at all, or text (which the repair pass set aside) with no markup.
      const char* first = text.data();
      const char* end = text.data() + text.size();
      if (text.substr(0, 3) == "\xEF\xBB\xBF") first += 3;
      while (first < end && detail::isXmlSpace(*first)) ++first;
      if (first == end) fail(0, "no <scene> element: the file is empty");
      if (std::memchr(first, '<', static_cast<std::size_t>(end - first)))
        fail(0, "no <scene> element: the file has no elements");
      const char* lineEnd = first;
      while (lineEnd < end && *lineEnd != '\n' && *lineEnd != '\r') ++lineEnd;
      fail(1 + detail::countNewlines(text.data(), first),
           "the file is not XML: no element found (it starts with " +
               quoted(std::string_view(first, static_cast<std::size_t>(lineEnd - first))) + ")");
    }
    case tinyxml2::XML_ERROR_PARSING_ATTRIBUTE: what = "malformed attribute"; break;
    case tinyxml2::XML_ERROR_PARSING_ELEMENT: what = "malformed element"; break;
    case tinyxml2::XML_ERROR_MISMATCHED_ELEMENT: what = "mismatched closing tag"; break;
    case tinyxml2::XML_ERROR_PARSING_TEXT: what = "malformed text (a literal '<' or '&' must be escaped)"; break;
    case tinyxml2::XML_ERROR_PARSING_COMMENT: what = "malformed comment"; break;
    case tinyxml2::XML_ERROR_PARSING_DECLARATION: what = "malformed <?...?> declaration"; break;
    case tinyxml2::XML_ERROR_PARSING_CDATA: what = "malformed CDATA section"; break;
    case tinyxml2::XML_ERROR_PARSING_UNKNOWN: what = "malformed <!...> declaration"; break;
    case tinyxml2::XML_ELEMENT_DEPTH_EXCEEDED: what = "elements nested too deeply"; break;
    default: what = doc.ErrorName(); break;
  }
  fail(doc.ErrorLineNum(), "XML syntax error: " + what);
}

// Built with append: GCC 12 warns (-Wrestrict, a false positive) on "<" + std::string(...).
std::string Loader::elementName(const XMLElement* e) {
  std::string s(1, '<');
  s.append(e->Name());
  s.push_back('>');
  return s;
}

bool Loader::isName(const XMLElement* e, std::string_view lowercase) {
  return detail::equalsIgnoreCase(e->Name(), lowercase);
}

std::string Loader::canonicalName(const XMLElement* e) {
  std::string name = toLower(e->Name());
  const std::string_view alias = detail::canonicalAlias(name);
  return alias.empty() ? name : std::string(alias);
}

std::string Loader::readName(const XMLElement* e) {
  const std::string name = toLower(e->Name());
  const std::string_view alias = detail::canonicalAlias(name);
  if (alias.empty()) return name;
  const std::string written = elementName(e);
  if (name == "backgroundcolor")
    nonconforming(e->GetLineNum(), written + " read as <background> (the handout example's spelling; the format's name is <background>)");
  else
    nonconforming(e->GetLineNum(), written + " read as <" + std::string(alias) + "> (misspelled element name)");
  return std::string(alias);
}

namespace {

bool isLightElement(std::string_view canonical) {
  bool found = false;
  SceneLights().forEachType([&](const auto& list) { found = found || LightOf<decltype(list)>::kType.element == canonical; });
  return found;
}

bool isLightField(std::string_view canonical) {
  bool found = false;
  SceneLights().forEachType([&](const auto& list) {
    for (const auto& field : LightOf<decltype(list)>::fields()) found = found || field.element == canonical;
  });
  return found;
}

}  // namespace

bool Loader::isKnownName(std::string_view canonical) {
  for (const TagName& t : kTagNames)
    if (t.name == canonical) return true;
  return isLightElement(canonical) || isLightField(canonical);
}

// The element's tag, after case folding and aliases (an alias is reported once per spelling).
Tag Loader::identify(const XMLElement* e) {
  const std::string canonical = readName(e);
  for (const TagName& t : kTagNames)
    if (t.name == canonical) return t.tag;
  return isLightElement(canonical) ? Tag::Light : Tag::Unknown;
}

namespace {

// Edits from `a` to `b` (insert, delete, replace, or swap two neighbours), at most `limit` + 1 reported.
std::size_t editDistance(std::string_view a, std::string_view b, std::size_t limit) {
  if ((a.size() > b.size() ? a.size() - b.size() : b.size() - a.size()) > limit) return limit + 1;
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
    for (std::size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

// A name this close to a known one is taken for a misspelling of it: two edits, and never most of a short name.
bool isLikelyMisspelling(std::string_view written, std::string_view known) {
  const std::size_t limit = known.size() <= 4 ? 1 : 2;
  return editDistance(written, known, limit) <= limit;
}

}  // namespace

std::string Loader::nearestKnownName(std::string_view canonical) {
  std::string best;
  std::size_t bestDistance = 3;
  const auto consider = [&](std::string_view known) {
    if (!isLikelyMisspelling(canonical, known)) return;
    const std::size_t distance = editDistance(canonical, known, 2);
    if (distance < bestDistance) bestDistance = distance, best = std::string(known);
  };
  for (const TagName& t : kTagNames) consider(t.name);
  SceneLights().forEachType([&](const auto& list) {
    consider(LightOf<decltype(list)>::kType.element);
    for (const auto& field : LightOf<decltype(list)>::fields()) consider(field.element);
  });
  return best;
}

void Loader::failMissing(const XMLElement* parent, int line, std::string_view missing, const std::string& message) {
  for (const XMLElement* child = parent->FirstChildElement(); child; child = child->NextSiblingElement()) {
    const std::string canonical = canonicalName(child);
    if (!isKnownName(canonical) && isLikelyMisspelling(canonical, missing))
      fail(child->GetLineNum(), "unknown element " + elementName(child) + " (did you mean <" + std::string(missing) +
                                    ">?): " + message);
  }
  fail(line, message);
}

void Loader::unknownElement(const XMLElement* e, const std::string& where) {
  const bool known = isKnownName(canonicalName(e));
  std::string message;
  if (known)
    message = "element " + elementName(e) + " is not expected " + where + "; ignored";
  else
    message = "unknown element " + elementName(e) + " ignored";
  if (const std::string nearest = known ? std::string() : nearestKnownName(canonicalName(e)); !nearest.empty())
    message += " (did you mean <" + nearest + ">?)";
  if (where == "inside <objects>" && !known) message += " (only <mesh> objects are part of the format)";
  nonconforming(e->GetLineNum(), message);
}

void Loader::strayText(const tinyxml2::XMLText* text) {
  std::string_view value = text->Value();
  std::size_t b = 0, e = value.size();
  while (b < e && detail::isXmlSpace(value[b])) ++b;
  while (e > b && detail::isXmlSpace(value[e - 1])) --e;
  if (b == e) return;
  nonconforming(text->GetLineNum(), "stray text " + quoted(value.substr(b, e - b)) + " ignored");
}

std::vector<Piece> Loader::textOf(const XMLElement* e) {
  std::vector<Piece> pieces;
  for (const XMLNode* node = e->FirstChild(); node; node = node->NextSibling()) {
    if (const tinyxml2::XMLText* text = node->ToText()) {
      pieces.push_back({text->Value(), text->GetLineNum()});
    } else if (const XMLElement* child = node->ToElement()) {
      unknownElement(child, "inside " + elementName(e));
    }
  }
  if (ceng477_) keepFirstText(e, pieces);
  return pieces;
}

int Loader::lineIn(const Piece& piece, const char* p) {
  const char* first = piece.text.data();
  const char* end = piece.text.data() + piece.text.size();
  while (first < end && detail::isXmlSpace(*first)) ++first;
  return piece.line + (p > first ? detail::countNewlines(first, p) : 0);
}

// Reads every number of an element into `out` (appending). `asFloat` also refuses values beyond float.
void Loader::readNumbers(const XMLElement* e, std::vector<double>& out, bool asFloat) {
  readNumbers(e, asFloat, [&](double v) { out.push_back(v); });
}

void Loader::readNumbers(const XMLElement* e, bool asFloat, const std::function<void(double)>& sink) {
  const std::vector<Piece> pieces = textOf(e);
  for (const Piece& piece : pieces) {
    detail::TokenScanner scanner(piece.text);
    double value = 0.0;
    NumberStatus status = NumberStatus::Ok;
    std::string_view token;
    bool glued = false;
    while (scanner.nextNumber(value, status, token, glued)) {
      if (status == NumberStatus::NotANumber)
        fail(lineIn(piece, token.data()), elementName(e) + ": expected a number, found " + quotedNumber(token));
      if (status == NumberStatus::NotFinite || (asFloat && std::fabs(value) > FLT_MAX))
        fail(lineIn(piece, token.data()), elementName(e) + ": " + quoted(token) + " is not a finite number" +
                                              (status == NumberStatus::Ok ? " in single precision" : ""));
      if (glued) {
        const char* tokenEnd = scanner.position();
        while (tokenEnd < piece.text.data() + piece.text.size() && !detail::isXmlSpace(*tokenEnd)) ++tokenEnd;
        nonconforming(lineIn(piece, token.data()),
                      elementName(e) + ": numbers not separated by whitespace in " +
                          quoted(std::string_view(token.data(), static_cast<std::size_t>(tokenEnd - token.data()))) +
                          " (read as separate numbers)");
      }
      sink(value);
    }
  }
}

// Exactly `count` finite numbers.
void Loader::readFixed(const XMLElement* e, std::size_t count, double* values, bool asFloat) {
  std::vector<double> numbers;
  readNumbers(e, numbers, asFloat);
  if (numbers.size() != count)
    fail(e->GetLineNum(), elementName(e) + ": expected " + plural(count, "number", "numbers") + ", found " +
                              std::to_string(numbers.size()));
  std::copy(numbers.begin(), numbers.end(), values);
}

glm::dvec3 Loader::readPoint(const XMLElement* e) {
  double v[3];
  readFixed(e, 3, v, false);
  return {v[0], v[1], v[2]};
}

Color Loader::readColor(const XMLElement* e) {
  double v[3];
  readFixed(e, 3, v, true);
  return Color(static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]));
}

// <metallicroughness>m r</metallicroughness>: two factors from 0 to 1, as glTF's.
void Loader::readMetallicRoughness(const XMLElement* e, Material& material) {
  double v[2];
  readFixed(e, 2, v, true);
  for (const double f : v)
    if (!(f >= 0.0 && f <= 1.0))
      fail(e->GetLineNum(), elementName(e) + ": metallic and roughness must be from 0 to 1, found " + trimmedText(e));
  material.metallic = static_cast<float>(v[0]);
  material.roughness = static_cast<float>(v[1]);
}

// <alphacutoff>c</alphacutoff>: a coverage from 0 to 1, as glTF's alphaCutoff.
void Loader::readAlphaCutoff(const XMLElement* e, Material& material) {
  const double c = readScalar(e, true);
  if (!(c >= 0.0 && c <= 1.0)) fail(e->GetLineNum(), elementName(e) + ": must be from 0 to 1, found " + trimmedText(e));
  material.alphaCutoff = static_cast<float>(c);
}

double Loader::readScalar(const XMLElement* e, bool asFloat) {
  double v;
  readFixed(e, 1, &v, asFloat);
  return v;
}

// Exactly `count` integers; `what` describes them for the message ("a non-negative integer").
void Loader::readIntegers(const XMLElement* e, std::size_t count, std::int64_t* values, std::int64_t minimum,
                  const std::string& what) {
  const std::vector<Piece> pieces = textOf(e);
  std::size_t found = 0;
  for (const Piece& piece : pieces) {
    detail::TokenScanner scanner(piece.text);
    std::int64_t value = 0;
    NumberStatus status = NumberStatus::Ok;
    std::string_view token;
    while (scanner.nextInteger(value, status, token)) {
      if (status != NumberStatus::Ok || value < minimum)
        fail(lineIn(piece, token.data()), elementName(e) + ": expected " + what + ", found " + quotedNumber(token));
      if (found < count) values[found] = value;
      ++found;
    }
  }
  if (found != count)
    fail(e->GetLineNum(), elementName(e) + ": expected " + what + ", found " + plural(found, "number", "numbers"));
}

std::string Loader::attribute(const XMLElement* e, std::string_view name) {
  for (const tinyxml2::XMLAttribute* a = e->FirstAttribute(); a; a = a->Next())
    if (detail::equalsIgnoreCase(a->Name(), name)) return a->Value();
  return {};
}

bool Loader::hasAttribute(const XMLElement* e, std::string_view name) {
  for (const tinyxml2::XMLAttribute* a = e->FirstAttribute(); a; a = a->Next())
    if (detail::equalsIgnoreCase(a->Name(), name)) return true;
  return false;
}

std::string Loader::trimmedText(const XMLElement* e) {
  std::string text;
  for (const Piece& piece : textOf(e)) text.append(piece.text);
  std::size_t b = text.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return {};
  std::size_t end = text.find_last_not_of(" \t\r\n");
  return text.substr(b, end - b + 1);
}

std::string Loader::trimmedNumber(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  return buffer;
}

// <pointlight id="1"> as written, for messages.
std::string Loader::describe(const XMLElement* e) {
  if (!hasAttribute(e, "id")) return elementName(e);
  std::string s = elementName(e);
  s.pop_back();
  return s + " id=\"" + attribute(e, "id") + "\">";
}

std::string quotedNumber(std::string_view token, std::string_view allowed) {
  constexpr int kMaxNamed = 3;
  std::string names;
  int named = 0;
  for (std::size_t i = 0; i < token.size() && i < 32; ++i) {
    const auto c = static_cast<unsigned char>(token[i]);
    if (allowed.find(static_cast<char>(c)) != std::string_view::npos) continue;
    if (named == kMaxNamed) {
      names += ", ...";
      break;
    }
    char name[48];
    if (std::isalpha(c)) std::snprintf(name, sizeof name, "letter %c", c);
    else if (c >= 0x80) std::snprintf(name, sizeof name, "non-ASCII byte 0x%02X", c);
    else if (std::isprint(c)) std::snprintf(name, sizeof name, "'%c'", c);
    else std::snprintf(name, sizeof name, "control character 0x%02X", c);
    names += (named++ == 0 ? "" : ", ") + std::string(name) + " at column " + std::to_string(i + 1);
  }
  return names.empty() ? quoted(token) : quoted(token) + " (" + names + ")";
}

}  // namespace rayview::scene_loading
