#pragma once
// What the viewer's workers receive, as bytes: the geometry once per scene (and traversal), then a small parameter
// snapshot per edit. Binary and exact (every double and float as its bits), so a worker's image is rank 0's bit for
// bit; a snapshot carries the hash of the parameters as the scene writer states them, which the worker checks, so
// a field the codec does not carry cannot go unnoticed. No MPI.

#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "rayview/render_settings.h"
#include "rayview/scene.h"
#include "rayview/scene_codec.h"

namespace rayview::cluster {

using rayview::Bytes;
using rayview::CodecError;

struct ShippedGeometry {
  std::shared_ptr<SceneGeometry> geometry;
  glm::dvec3 origin{0.0};  // the traversal's origin (prepareGeometry's): rank 0's, not recomputed
  AccelKind accel = AccelKind::Embree;
  // The parameters sent with it, for the materials its cut-outs come from (the viewer's workers build their BVH
  // before any snapshot); none when the sender gave none.
  std::optional<SceneParameters> parameters;
};

Bytes encodeGeometry(const SceneGeometry& geometry, const glm::dvec3& origin, AccelKind accel,
                     const SceneParameters* parameters = nullptr);
ShippedGeometry decodeGeometry(const std::uint8_t* data, std::size_t size);

struct Snapshot {
  SceneParameters parameters;
  RenderSettings settings;
};

Bytes encodeSnapshot(const SceneParameters& parameters, const RenderSettings& settings);
// Throws CodecError when the bytes are malformed or the parameters' hash differs from the sender's.
Snapshot decodeSnapshot(const std::uint8_t* data, std::size_t size);

}  // namespace rayview::cluster
