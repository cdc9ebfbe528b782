#pragma once
// Exposure and gamma: how the viewer shows the render's 8-bit image, never how it renders it. Changing them
// maps the image on screen again and never restarts the render. No GL: the viewer uploads what this hands it.

#include <cstdint>
#include <string>

#include "rayview/image.h"

namespace rayview {

// The limits the panel's sliders and the `set exposure` / `set gamma` script commands accept.
inline constexpr float kMinExposureStops = -8.0f;
inline constexpr float kMaxExposureStops = 8.0f;
inline constexpr float kMinGamma = 0.2f;
inline constexpr float kMaxGamma = 5.0f;

// The defaults (0 stops, gamma 1) show the image exactly as the course computes it: every channel clamped to
// 0..255, no gamma.
struct DisplayMapping {
  float exposureStops = 0.0f;  // each value times 2^stops, then clamped to 255
  float gamma = 1.0f;          // then v^(1/gamma), v in 0..1: above 1 brightens the mid-tones, below 1 darkens them

  bool operator==(const DisplayMapping&) const = default;
  bool identity() const { return *this == DisplayMapping{}; }
};

// The level shown for one channel's `level`: 255 * min(1, level / 255 * 2^stops)^(1 / gamma), rounded to the
// nearest. A value the render clipped at 255 stays one value: exposure cannot bring back what it clipped.
std::uint8_t displayLevel(std::uint8_t level, const DisplayMapping& mapping);

// `raw` as shown: every channel through displayLevel.
Image mapForDisplay(const Image& raw, const DisplayMapping& mapping);

// "exposure +1 stops, gamma 2.2": for messages.
std::string describe(const DisplayMapping& mapping);

// What a frame save writes: the image as `rayview render` writes it, or as the image area shows it.
// Raw: the render as `rayview render` writes it. Displayed: with exposure and gamma. View: the image area as
// seen (zoom, exposure, reference or difference), read back from the window.
enum class FrameSave { Raw, Displayed, View };

// The image shown for one source of images (the render's passes, the reference): mapped again only when the
// source's version or the mapping changed. At the defaults it is the source's image itself, never a copy.
class MappedImage {
 public:
  const Image& of(const Image& raw, std::uint64_t version, const DisplayMapping& mapping);
  // Increases whenever of() hands out another image: the texture is uploaded again.
  std::uint64_t serial() const { return serial_; }

 private:
  Image mapped_;
  std::uint64_t version_ = 0;
  DisplayMapping mapping_;
  bool mappedOnce_ = false;
  std::uint64_t serial_ = 0;
};

}  // namespace rayview
