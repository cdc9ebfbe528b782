#include "view_codec.h"

#include "scene_hash.h"

namespace rayview::cluster {
namespace {

// Bumped with any change of the layout: a rank of another build is refused rather than misread.
constexpr std::uint32_t kGeometryMagic = 0x52564733;  // "RVG3"
constexpr std::uint32_t kSnapshotMagic = 0x52565332;  // "RVS2"

void checkEnd(std::size_t at, std::size_t size) {
  if (at != size) throw CodecError("trailing bytes");
}

}  // namespace

Bytes encodeGeometry(const SceneGeometry& g, const glm::dvec3& origin, AccelKind accel,
                     const SceneParameters* parameters) {
  Bytes out;
  encodeValue(kGeometryMagic, out);
  encodeValue(origin, out);
  encodeValue(static_cast<std::uint8_t>(accel), out);
  rayview::encodeGeometry(g, out);
  encodeValue(static_cast<std::uint8_t>(parameters != nullptr), out);
  if (parameters) encodeParameters(*parameters, out);
  return out;
}

ShippedGeometry decodeGeometry(const std::uint8_t* data, std::size_t size) {
  std::size_t at = 0;
  if (decodeValue<std::uint32_t>(data, size, at) != kGeometryMagic) throw CodecError("not a rayview geometry message");
  ShippedGeometry shipped;
  shipped.origin = decodeValue<glm::dvec3>(data, size, at);
  const auto accel = decodeValue<std::uint8_t>(data, size, at);
  if (accel >= kAccelKindCount) throw CodecError("unknown traversal");
  shipped.accel = static_cast<AccelKind>(accel);
  shipped.geometry = std::make_shared<SceneGeometry>(rayview::decodeGeometry(data, size, at));
  const auto withParameters = decodeValue<std::uint8_t>(data, size, at);
  if (withParameters > 1) throw CodecError("malformed geometry message");
  if (withParameters) shipped.parameters = decodeParameters(data, size, at);
  checkEnd(at, size);
  return shipped;
}

Bytes encodeSnapshot(const SceneParameters& p, const RenderSettings& settings) {
  Bytes out;
  encodeValue(kSnapshotMagic, out);
  encodeValue(parametersHash(p), out);
  encodeValue(settings, out);
  encodeParameters(p, out);
  return out;
}

Snapshot decodeSnapshot(const std::uint8_t* data, std::size_t size) {
  std::size_t at = 0;
  if (decodeValue<std::uint32_t>(data, size, at) != kSnapshotMagic) throw CodecError("not a rayview snapshot message");
  const auto hash = decodeValue<std::uint64_t>(data, size, at);
  Snapshot s;
  s.settings = decodeValue<RenderSettings>(data, size, at);
  s.parameters = decodeParameters(data, size, at);
  checkEnd(at, size);
  if (parametersHash(s.parameters) != hash) throw CodecError("the parameters differ from rank 0's after decoding");
  return s;
}

}  // namespace rayview::cluster
