// Binary PPM (P6) and PGM (P5), read by rayview itself: Debian 12's stb_image overflows a signed int on a long
// number in a PNM header (found by fuzzing; tests/fuzz_regressions/texture/). Every number here is checked.
#include "pnm_decode.h"

#include <cctype>
#include <cstdint>

#include "rayview/image_limits.h"

namespace rayview::detail {
namespace {

class HeaderReader {
 public:
  explicit HeaderReader(std::string_view bytes) : bytes_(bytes), at_(2) {}

  // The next decimal number after whitespace and comments, at most `limit`; nothing when there is none.
  std::optional<long long> number(long long limit) {
    skipSpaceAndComments();
    if (at_ >= bytes_.size() || !std::isdigit(static_cast<unsigned char>(bytes_[at_]))) return std::nullopt;
    long long value = 0;
    while (at_ < bytes_.size() && std::isdigit(static_cast<unsigned char>(bytes_[at_]))) {
      value = value * 10 + (bytes_[at_++] - '0');
      if (value > limit) return std::nullopt;
    }
    return value;
  }

  // After the last header number: exactly one whitespace byte, then the samples.
  bool endOfHeader() {
    if (at_ >= bytes_.size() || !std::isspace(static_cast<unsigned char>(bytes_[at_]))) return false;
    ++at_;
    return true;
  }
  std::size_t position() const { return at_; }

 private:
  void skipSpaceAndComments() {
    while (at_ < bytes_.size()) {
      const unsigned char c = static_cast<unsigned char>(bytes_[at_]);
      if (std::isspace(c)) {
        ++at_;
      } else if (c == '#') {
        while (at_ < bytes_.size() && bytes_[at_] != '\n' && bytes_[at_] != '\r') ++at_;
      } else {
        return;
      }
    }
  }

  std::string_view bytes_;
  std::size_t at_;
};

}  // namespace

bool looksLikePnm(std::string_view bytes) {
  return bytes.size() >= 2 && bytes[0] == 'P' && (bytes[1] == '5' || bytes[1] == '6');
}

std::optional<Texture> decodePnm(std::string_view bytes, long long maxPixels, std::string& reason) {
  const int channels = bytes[1] == '6' ? 3 : 1;
  HeaderReader header(bytes);
  const std::optional<long long> width = header.number(1LL << 30), height = header.number(1LL << 30),
                                 maxValue = header.number(65535);
  if (!width || !height || !maxValue || *width < 1 || *height < 1 || *maxValue < 1 || !header.endOfHeader()) {
    reason = "cannot be decoded (a PNM header needs a width, a height and a maximum value from 1 to 65535)";
    return std::nullopt;
  }
  if (std::string problem = imageSizeProblem(*width, *height); !problem.empty() || *width * *height > maxPixels) {
    reason = imageSizeProblem(*width, *height);
    return std::nullopt;
  }
  const int bytesPerSample = *maxValue > 255 ? 2 : 1;
  const std::size_t pixels = static_cast<std::size_t>(*width) * static_cast<std::size_t>(*height);
  const std::size_t needed = pixels * channels * bytesPerSample;
  if (bytes.size() - header.position() < needed) {
    reason = "cannot be decoded (the PNM file ends before its samples do)";
    return std::nullopt;
  }
  const auto* in = reinterpret_cast<const unsigned char*>(bytes.data() + header.position());
  Texture texture;
  texture.width = static_cast<int>(*width);
  texture.height = static_cast<int>(*height);
  texture.rgb.resize(pixels * 3);
  // Each sample scaled from 0..maxval to 0..255, rounded: a maxval-1 white is 255, a 16-bit sample (big-endian, as
  // the format stores it) is v * 255 / maxval. A sample over maxval is not a value the file can hold.
  const unsigned maxval = static_cast<unsigned>(*maxValue);
  for (std::size_t p = 0; p < pixels; ++p)
    for (int c = 0; c < 3; ++c) {
      const std::size_t sample = (p * channels + (channels == 3 ? c : 0)) * bytesPerSample;
      const unsigned value = bytesPerSample == 2 ? (unsigned{in[sample]} << 8) | in[sample + 1] : in[sample];
      if (value > maxval) {
        reason = "cannot be decoded (a sample is " + std::to_string(value) + ", over the maximum value " +
                 std::to_string(maxval) + ")";
        return std::nullopt;
      }
      texture.rgb[p * 3 + c] = static_cast<std::uint8_t>((value * 255u + maxval / 2) / maxval);
    }
  return texture;
}

}  // namespace rayview::detail
