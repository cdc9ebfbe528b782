#pragma once
// Whitespace-separated numbers straight from an element's text: std::from_chars, no streams, no allocation.

#include <cstddef>
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

// The bytes of a block's text the loader judges its length by (estimatedItems): enough for thousands of items.
inline constexpr std::size_t kEstimateSample = std::size_t{1} << 16;

// How many items of `tokensPerItem` tokens a block of `totalBytes` bytes of text holds, judged by the tokens of
// `sample`, its first bytes (all of it when `totalBytes` fits): what the loader reserves before it reads the
// block. At least the items the sample's density gives, and slightly more (long blocks write their later indices
// with more digits, which only lowers the density): never a multiple of what is needed, as a bound from the
// shortest possible token would be ("1 2 3" against "50000//50000 ...": six times the faces, docs/PERFORMANCE.md,
// "The loader"). An estimate only: arrays still grow when a block holds more.
std::size_t estimatedItems(std::string_view sample, std::uint64_t totalBytes, std::size_t tokensPerItem);

}  // namespace rayview::detail
