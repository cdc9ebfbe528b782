#pragma once
// What a render computes, one pixel at a time. The progressive renderer and the tests see only this;
// TracedImage is the real one (scene parameters, its geometry and the settings, owned together).

#include <memory>

#include "rayview/prepared_scene.h"
#include "rayview/tracer.h"

namespace rayview {

class PixelSource {
 public:
  virtual ~PixelSource() = default;
  virtual int width() const = 0;
  virtual int height() const = 0;
  // Radiance of pixel (x, y); must be a pure function of (x, y): called from many threads at once.
  virtual Color pixel(int x, int y, RayCounts& counts) const = 0;
  // Anti-aliasing: pixel() is the mean of samplesPerPixel() samples, (sample(0) + sample(1) + ...) / N summed
  // in that order in float, so the progressive renderer can accumulate them pass by pass and end bit-identical.
  virtual int samplesPerPixel() const { return 1; }
  // How the radiance becomes 8-bit channels (RenderSettings::quantization).
  virtual Quantization quantization() const { return Quantization::Round; }
  virtual Color sample(int x, int y, int k, RayCounts& counts) const { return k == 0 ? pixel(x, y, counts) : Color(0.0f); }
  // The same for `count` pixels at once (out[n] for pixels[n]), bit for bit: a source may trace them together.
  virtual void pixels(const PixelXY* pixels, int count, Color* out, RayCounts& counts) const {
    for (int n = 0; n < count; ++n) out[n] = pixel(pixels[n].x, pixels[n].y, counts);
  }
  virtual void samples(const PixelXY* pixels, int count, int k, Color* out, RayCounts& counts) const {
    for (int n = 0; n < count; ++n) out[n] = sample(pixels[n].x, pixels[n].y, k, counts);
  }
};

// A parameter snapshot, the prepared geometry and the settings, kept alive together for as long as a render
// uses them. The viewer edits its own SceneParameters and hands a new snapshot to each restart.
class TracedImage final : public PixelSource {
 public:
  TracedImage(std::shared_ptr<const SceneParameters> parameters, std::shared_ptr<const PreparedGeometry> geometry,
              const RenderSettings& settings);
  int width() const override { return parameters_->camera.width; }
  int height() const override { return parameters_->camera.height; }
  Color pixel(int x, int y, RayCounts& counts) const override { return tracer_.tracePixel(x, y, counts); }
  int samplesPerPixel() const override { return tracer_.pixelSamples(); }
  Quantization quantization() const override { return tracer_.quantization(); }
  Color sample(int x, int y, int k, RayCounts& counts) const override { return tracer_.traceSample(x, y, k, counts); }
  void pixels(const PixelXY* pixels, int count, Color* out, RayCounts& counts) const override {
    tracer_.tracePixels(pixels, count, out, counts);
  }
  void samples(const PixelXY* pixels, int count, int k, Color* out, RayCounts& counts) const override {
    tracer_.traceSamples(pixels, count, k, out, counts);
  }
  const Tracer& tracer() const { return tracer_; }
  // What it was made of: what another process needs to make the same image (cluster/viewer_farm.cpp).
  const std::shared_ptr<const SceneParameters>& parameters() const { return parameters_; }
  const std::shared_ptr<const PreparedGeometry>& geometry() const { return geometry_; }
  const RenderSettings& settings() const { return settings_; }

 private:
  std::shared_ptr<const SceneParameters> parameters_;
  std::shared_ptr<const PreparedGeometry> geometry_;
  RenderSettings settings_;
  Tracer tracer_;
};

}  // namespace rayview
