#pragma once
// The whole of a model file in memory, read by rayview's own STL reader (and handed whole to the
// renderer's PLY reader): binary fields and ASCII tokens.

#include <bit>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>

namespace rayview::model {

// Reads a file whole; "" and `problem` set when it cannot.
std::string readWholeFile(const std::filesystem::path& path, std::string& problem);

// Whitespace-separated tokens of ASCII text, with their line numbers.
class Tokens {
 public:
  explicit Tokens(std::string_view text, std::size_t at = 0) : text_(text), at_(at) {}
  // The next token ("" at the end).
  std::string_view next() {
    while (at_ < text_.size() && isSpace(text_[at_])) {
      if (text_[at_] == '\n') ++line_;
      ++at_;
    }
    const std::size_t start = at_;
    while (at_ < text_.size() && !isSpace(text_[at_])) ++at_;
    return text_.substr(start, at_ - start);
  }
  bool number(double& value) {
    const std::string_view token = next();
    const char* first = token.data();
    if (!token.empty() && token[0] == '+') ++first;
    const auto result = std::from_chars(first, token.data() + token.size(), value);
    return !token.empty() && result.ec == std::errc() && result.ptr == token.data() + token.size();
  }
  int line() const { return line_; }
  std::size_t position() const { return at_; }

 private:
  static bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }
  std::string_view text_;
  std::size_t at_;
  int line_ = 1;
};

// A little- or big-endian scalar at `p`.
template <class T>
T loadScalar(const char* p, bool bigEndian) {
  T value;
  std::memcpy(&value, p, sizeof value);
  if (bigEndian && sizeof(T) > 1) {
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof value);
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
    std::memcpy(&value, bytes, sizeof value);
  }
  return value;
}

}  // namespace rayview::model
