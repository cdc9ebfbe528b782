#include "view_codec.h"

#include <cstring>
#include <type_traits>

#include "scene_hash.h"

namespace rayview::cluster {
namespace {

// Bumped with any change of the layout: a rank of another build is refused rather than misread.
constexpr std::uint32_t kGeometryMagic = 0x52564733;  // "RVG3"
constexpr std::uint32_t kSnapshotMagic = 0x52565332;  // "RVS2"

template <class T>
void put(Bytes& out, const T& value) {
  static_assert(std::is_trivially_copyable_v<T>);
  const auto* p = reinterpret_cast<const std::uint8_t*>(&value);
  out.insert(out.end(), p, p + sizeof value);
}

template <class T>
T take(const std::uint8_t* data, std::size_t size, std::size_t& at) {
  static_assert(std::is_trivially_copyable_v<T>);
  if (sizeof(T) > size - at) throw CodecError("truncated");
  T value;
  std::memcpy(&value, data + at, sizeof value);
  at += sizeof value;
  return value;
}

void checkEnd(std::size_t at, std::size_t size) {
  if (at != size) throw CodecError("trailing bytes");
}

}  // namespace

Bytes encodeGeometry(const SceneGeometry& g, const glm::dvec3& origin, AccelKind accel,
                     const SceneParameters* parameters) {
  Bytes out;
  put(out, kGeometryMagic);
  put(out, origin);
  put(out, static_cast<std::uint8_t>(accel));
  rayview::encodeGeometry(g, out);
  put(out, static_cast<std::uint8_t>(parameters != nullptr));
  if (parameters) encodeParameters(*parameters, out);
  return out;
}

ShippedGeometry decodeGeometry(const std::uint8_t* data, std::size_t size) {
  std::size_t at = 0;
  if (take<std::uint32_t>(data, size, at) != kGeometryMagic) throw CodecError("not a rayview geometry message");
  ShippedGeometry shipped;
  shipped.origin = take<glm::dvec3>(data, size, at);
  const auto accel = take<std::uint8_t>(data, size, at);
  if (accel >= kAccelKindCount) throw CodecError("unknown traversal");
  shipped.accel = static_cast<AccelKind>(accel);
  shipped.geometry = std::make_shared<SceneGeometry>(rayview::decodeGeometry(data, size, at));
  const auto withParameters = take<std::uint8_t>(data, size, at);
  if (withParameters > 1) throw CodecError("malformed geometry message");
  if (withParameters) shipped.parameters = decodeParameters(data, size, at);
  checkEnd(at, size);
  return shipped;
}

Bytes encodeSnapshot(const SceneParameters& p, const RenderSettings& settings) {
  Bytes out;
  put(out, kSnapshotMagic);
  put(out, parametersHash(p));
  put(out, settings);
  encodeParameters(p, out);
  return out;
}

Snapshot decodeSnapshot(const std::uint8_t* data, std::size_t size) {
  std::size_t at = 0;
  if (take<std::uint32_t>(data, size, at) != kSnapshotMagic) throw CodecError("not a rayview snapshot message");
  const auto hash = take<std::uint64_t>(data, size, at);
  Snapshot s;
  s.settings = take<RenderSettings>(data, size, at);
  s.parameters = decodeParameters(data, size, at);
  checkEnd(at, size);
  if (parametersHash(s.parameters) != hash) throw CodecError("the parameters differ from rank 0's after decoding");
  return s;
}

}  // namespace rayview::cluster
