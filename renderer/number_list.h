#pragma once
// Whitespace-separated numbers straight from an element's text: std::from_chars, no streams, no allocation.

#include <cstdint>
#include <string_view>

namespace rayview::detail {

enum class NumberStatus {
  Ok,
  NotANumber,   // the token is not a number at all ("x", "1,2", "")
  NotFinite,    // "nan", "inf", or a value too large for a double
  NotInteger,   // a number, but an integer was expected ("1.5")
};

inline bool isXmlSpace(char c) { return c == ' ' || c == '\n' || c == '\t' || c == '\r'; }

// Walks the tokens of a text. A token is a maximal run of non-whitespace characters, except that
// a sign glued to the end of a number ("1-1") starts a new token: nextNumber() reports that as `glued`.
class TokenScanner {
 public:
  explicit TokenScanner(std::string_view text) : begin_(text.data()), p_(text.data()), end_(text.data() + text.size()) {}

  // The next whitespace-separated token, or an empty view at the end.
  std::string_view nextToken();

  // Parses the next token as a finite double. Returns false at the end of the text. On failure `status`
  // says why and `token` is the offending token. `glued` is set when the number was immediately
  // followed by a sign (the rest of the token is left for the next call).
  bool nextNumber(double& value, NumberStatus& status, std::string_view& token, bool& glued);

  // Parses the next token as an integer (decimal, optional sign). Same contract as nextNumber.
  bool nextInteger(std::int64_t& value, NumberStatus& status, std::string_view& token);

  const char* position() const { return p_; }
  const char* begin() const { return begin_; }
  bool atEnd();  // only whitespace left

 private:
  void skipSpace() {
    while (p_ < end_ && isXmlSpace(*p_)) ++p_;
  }
  const char* begin_;
  const char* p_;
  const char* end_;
};

// Whole-token parses (the token has no surrounding whitespace).
NumberStatus parseDouble(std::string_view token, double& value);
NumberStatus parseInteger(std::string_view token, std::int64_t& value);

// Number of '\n' in [begin, end).
int countNewlines(const char* begin, const char* end);

}  // namespace rayview::detail
