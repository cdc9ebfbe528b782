#include "number_list.h"

#include <algorithm>
#include <charconv>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <string>

namespace rayview::detail {

namespace {

// from_chars rejects a leading '+', which some exporters write.
const char* skipPlus(const char* p, const char* end) {
  if (p + 1 < end && *p == '+' && (std::isdigit(static_cast<unsigned char>(p[1])) || p[1] == '.')) return p + 1;
  return p;
}

// from_chars reports both overflow and underflow as result_out_of_range and leaves the value alone.
// Underflow is harmless (the value is 0 or subnormal); overflow is not a finite number.
bool underflows(const char* first, const char* last) {
  std::string copy(first, last);
  double v = std::strtod(copy.c_str(), nullptr);
  return std::isfinite(v);
}

// Parses a double at [p, end); returns the end of the number (== p when there is none).
const char* scanDouble(const char* p, const char* end, double& value, NumberStatus& status) {
  const char* start = skipPlus(p, end);
  auto [ptr, ec] = std::from_chars(start, end, value, std::chars_format::general);
  if (ptr == start) {
    status = NumberStatus::NotANumber;
    return p;
  }
  if (ec == std::errc::result_out_of_range) {
    if (underflows(start, ptr)) {
      value = std::strtod(std::string(start, ptr).c_str(), nullptr);
      status = NumberStatus::Ok;
    } else {
      status = NumberStatus::NotFinite;
    }
    return ptr;
  }
  status = std::isfinite(value) ? NumberStatus::Ok : NumberStatus::NotFinite;
  return ptr;
}

}  // namespace

std::string_view TokenScanner::nextToken() {
  skipSpace();
  const char* start = p_;
  while (p_ < end_ && !isXmlSpace(*p_)) ++p_;
  return {start, static_cast<std::size_t>(p_ - start)};
}

bool TokenScanner::atEnd() {
  skipSpace();
  return p_ == end_;
}

bool TokenScanner::nextNumber(double& value, NumberStatus& status, std::string_view& token, bool& glued) {
  glued = false;
  skipSpace();
  if (p_ == end_) return false;
  const char* start = p_;
  const char* stop = scanDouble(p_, end_, value, status);
  if (stop == end_ || isXmlSpace(*stop)) {
    token = {start, static_cast<std::size_t>(stop - start)};
    p_ = stop;
    return true;
  }
  // "1-1": a number immediately followed by a signed number.
  if (status == NumberStatus::Ok && stop > start && (*stop == '-' || *stop == '+') && stop + 1 < end_ &&
      (std::isdigit(static_cast<unsigned char>(stop[1])) || stop[1] == '.')) {
    token = {start, static_cast<std::size_t>(stop - start)};
    p_ = stop;
    glued = true;
    return true;
  }
  // Anything else glued to the number makes the whole token garbage.
  while (p_ < end_ && !isXmlSpace(*p_)) ++p_;
  token = {start, static_cast<std::size_t>(p_ - start)};
  status = NumberStatus::NotANumber;
  return true;
}

bool TokenScanner::nextInteger(std::int64_t& value, NumberStatus& status, std::string_view& token) {
  token = nextToken();
  if (token.empty()) return false;
  status = parseInteger(token, value);
  return true;
}

NumberStatus parseDouble(std::string_view token, double& value) {
  const char* end = token.data() + token.size();
  NumberStatus status = NumberStatus::NotANumber;
  const char* stop = scanDouble(token.data(), end, value, status);
  if (stop != end) return NumberStatus::NotANumber;
  return status;
}

NumberStatus parseInteger(std::string_view token, std::int64_t& value) {
  const char* end = token.data() + token.size();
  const char* start = skipPlus(token.data(), end);
  auto [ptr, ec] = std::from_chars(start, end, value);
  if (ptr == start) return NumberStatus::NotANumber;
  if (ptr == end) return ec == std::errc::result_out_of_range ? NumberStatus::NotFinite : NumberStatus::Ok;
  // Not a plain integer: say whether it is a number of another kind.
  double d = 0.0;
  NumberStatus asDouble = parseDouble(token, d);
  if (asDouble == NumberStatus::Ok) return NumberStatus::NotInteger;
  return asDouble;
}

int countNewlines(const char* begin, const char* end) {
  return static_cast<int>(std::count(begin, end, '\n'));
}

std::size_t estimatedItems(std::string_view sample, std::uint64_t totalBytes, std::size_t tokensPerItem) {
  std::uint64_t tokens = 0;
  TokenScanner scanner(sample);
  while (!scanner.nextToken().empty()) ++tokens;
  if (sample.empty() || tokensPerItem == 0) return 1;
  if (sample.size() >= totalBytes) return static_cast<std::size_t>(tokens / tokensPerItem + 1);
  // The sample's density over the whole block, 1/16 more; a token needs a byte and a separator, so never more
  // than half the bytes are tokens (a bound on the reserve however odd the sample).
  const double perByte = static_cast<double>(tokens) / static_cast<double>(sample.size());
  const double items = static_cast<double>(totalBytes) * std::min(perByte, 0.5) * (17.0 / 16.0) /
                       static_cast<double>(tokensPerItem);
  return static_cast<std::size_t>(items) + 16;
}

}  // namespace rayview::detail
