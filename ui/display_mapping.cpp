#include "display_mapping.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "rayview/scene_writer.h"

namespace rayview {
namespace {

using LevelTable = std::array<std::uint8_t, 256>;

LevelTable levelTable(const DisplayMapping& mapping) {
  LevelTable table{};
  for (std::size_t level = 0; level < table.size(); ++level)
    table[level] = displayLevel(static_cast<std::uint8_t>(level), mapping);
  return table;
}

}  // namespace

std::uint8_t displayLevel(std::uint8_t level, const DisplayMapping& mapping) {
  // In double: at +1 stop, 255 * (v / 255 * 2) lands within an ulp of 2v and rounds to exactly 2v.
  const double exposed = std::min(1.0, level / 255.0 * std::exp2(static_cast<double>(mapping.exposureStops)));
  const double shown = std::pow(exposed, 1.0 / static_cast<double>(mapping.gamma));
  return static_cast<std::uint8_t>(std::lround(255.0 * shown));
}

Image mapForDisplay(const Image& raw, const DisplayMapping& mapping) {
  const LevelTable table = levelTable(mapping);
  Image shown = raw;
  for (std::uint8_t& value : shown.rgb) value = table[value];
  return shown;
}

std::string describe(const DisplayMapping& mapping) {
  return std::string("exposure ") + (mapping.exposureStops > 0.0f ? "+" : "") + formatNumber(mapping.exposureStops) +
         " stops, gamma " + formatNumber(mapping.gamma);
}

const Image& MappedImage::of(const Image& raw, std::uint64_t version, const DisplayMapping& mapping) {
  if (!mappedOnce_ || version != version_ || mapping != mapping_) {
    mappedOnce_ = true;
    version_ = version;
    mapping_ = mapping;
    ++serial_;
    // At the defaults the source is shown as it is: no copy, no work per pass.
    if (!mapping.identity()) mapped_ = mapForDisplay(raw, mapping);
  }
  return mapping.identity() ? raw : mapped_;
}

}  // namespace rayview
