#include "scene_orders.h"

#include <cstring>

namespace rayview::cluster {
namespace {

constexpr std::uint32_t kOrderMagic = 0x52564f31;  // "RVO1": a rank of another build is refused

void put(Bytes& out, const void* data, std::size_t bytes) {
  const std::size_t at = out.size();
  out.resize(at + bytes);
  if (bytes > 0) std::memcpy(out.data() + at, data, bytes);
}

template <class T>
void putValue(Bytes& out, T value) {
  put(out, &value, sizeof value);
}

class Cursor {
 public:
  Cursor(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  void take(void* into, std::size_t bytes) {
    if (bytes > size_ - at_) throw CodecError("a scene order ends early");
    if (bytes > 0) std::memcpy(into, data_ + at_, bytes);
    at_ += bytes;
  }
  template <class T>
  T value() {
    T v{};
    take(&v, sizeof v);
    return v;
  }
  // A length-prefixed block, checked against what is left before anything is allocated.
  std::size_t length(std::size_t unit) {
    const auto n = value<std::uint64_t>();
    if (n > (size_ - at_) / unit) throw CodecError("a scene order's length is past its end");
    return static_cast<std::size_t>(n);
  }
  bool done() const { return at_ == size_; }

 private:
  const std::uint8_t* data_;
  std::size_t size_, at_ = 0;
};

void putBlock(Bytes& out, const void* data, std::size_t count, std::size_t unit) {
  putValue<std::uint64_t>(out, count);
  put(out, data, count * unit);
}

}  // namespace

std::vector<SceneRun> sceneRuns(const std::vector<FrameJob>& frames) {
  std::vector<SceneRun> runs;
  for (std::size_t first = 0; first < frames.size();) {
    std::size_t end = first;
    while (end < frames.size() && sameSceneAndCamera(frames[end], frames[first])) ++end;
    runs.push_back({first, end});
    first = end;
  }
  return runs;
}

Bytes encodeSceneOrder(const SceneOrder& order) {
  Bytes out;
  out.reserve(order.geometry.size() + order.parameters.size() + order.scenePath.size() + 64);
  putValue(out, kOrderMagic);
  putValue(out, order.run);
  putBlock(out, order.scenePath.data(), order.scenePath.size(), 1);
  putBlock(out, order.frames.data(), order.frames.size(), sizeof(std::int32_t));
  putBlock(out, order.geometry.data(), order.geometry.size(), 1);
  putBlock(out, order.parameters.data(), order.parameters.size(), 1);
  return out;
}

SceneOrder decodeSceneOrder(const std::uint8_t* data, std::size_t size) {
  Cursor in(data, size);
  if (in.value<std::uint32_t>() != kOrderMagic) throw CodecError("not a scene order of this build");
  SceneOrder order;
  order.run = in.value<std::int32_t>();
  order.scenePath.resize(in.length(1));
  in.take(order.scenePath.data(), order.scenePath.size());
  order.frames.resize(in.length(sizeof(std::int32_t)));
  in.take(order.frames.data(), order.frames.size() * sizeof(std::int32_t));
  if (order.frames.empty() || order.frames.size() % 2 != 0) throw CodecError("a scene order without whole frames");
  order.geometry.resize(in.length(1));
  in.take(order.geometry.data(), order.geometry.size());
  order.parameters.resize(in.length(1));
  in.take(order.parameters.data(), order.parameters.size());
  if (!in.done()) throw CodecError("a scene order runs past its end");
  return order;
}

}  // namespace rayview::cluster
