#pragma once
// A scene's geometry and parameters as bytes, exact (every double and float as its bits, native byte order: both
// ends are the same build). The one codec for what travels between processes: the import worker's answer and the
// export it is asked for (import/), and what rank 0 sends the other ranks under mpirun (cluster/).

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "rayview/scene.h"

namespace rayview {

using Bytes = std::vector<std::uint8_t>;

// Malformed bytes (a truncated message, another build's). Counts are checked against the bytes left before anything
// is allocated.
class CodecError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Appends `bytes` bytes at `data` to `out`; reads `bytes` bytes at `data[at..]` into `to`, moving `at` past them
// (CodecError "truncated" when fewer are left). Both codecs' values go through these.
void appendBytes(const void* data, std::size_t bytes, Bytes& out);
void readBytes(const std::uint8_t* data, std::size_t size, std::size_t& at, void* to, std::size_t bytes);

// One trivially copyable value as its bytes, and back.
template <class T>
void encodeValue(const T& value, Bytes& out) {
  static_assert(std::is_trivially_copyable_v<T>);
  appendBytes(&value, sizeof value, out);
}
template <class T>
T decodeValue(const std::uint8_t* data, std::size_t size, std::size_t& at) {
  static_assert(std::is_trivially_copyable_v<T>);
  T value;
  readBytes(data, size, at, &value, sizeof value);
  return value;
}

// Appends the geometry (vertices, texture coordinates, normals, triangles, face attributes, meshes, the texture's
// name and pixels) to `out`.
void encodeGeometry(const SceneGeometry& geometry, Bytes& out);
// Reads what encodeGeometry wrote at `data[at..]`, moving `at` past it. Throws CodecError.
SceneGeometry decodeGeometry(const std::uint8_t* data, std::size_t size, std::size_t& at);

// The same for the parameters: camera, lights, materials, background, ambient light, depth, shadow-ray epsilon.
void encodeParameters(const SceneParameters& parameters, Bytes& out);
SceneParameters decodeParameters(const std::uint8_t* data, std::size_t size, std::size_t& at);

}  // namespace rayview
