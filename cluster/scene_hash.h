#pragma once
// A fingerprint of a loaded scene, so that rank 0 can check that every rank holds the same one before their
// tiles are put together into one image.

#include <cstdint>

#include "rayview/scene.h"

namespace rayview::cluster {

// 64 bits over the parameters (as the scene writer states them) and every geometry array, texture included.
// Equal scenes give equal hashes on every machine of the same byte order; not a cryptographic hash.
std::uint64_t sceneHash(const Scene& scene);
// The same over the parameters alone.
std::uint64_t parametersHash(const SceneParameters& parameters);

}  // namespace rayview::cluster
