#include "rayview/render_job.h"

#include <cstring>
#include <type_traits>

#include "rayview/frame_plan.h"
#include "single_render.h"

namespace rayview {

const std::string& RenderJob::scene() const {
  static const std::string kDefault;
  return scenes.empty() ? kDefault : scenes.front();
}

RenderSettings renderSettingsOf(const RenderJob& job) {
  RenderSettings settings;
  applyKnobs(job.knobs, {nullptr, &settings});
  return settings;
}

int runRenderJob(const RenderJob& job) {
  return isFrameJob(job) ? runFramesJob(job) : runSingleRender(job);
}

namespace {

// Bumped with any change of the layout: a rank of another build is refused rather than misread.
constexpr std::uint32_t kJobMagic = 0x52564a33;  // "RVJ3"

class JobWriter {
 public:
  template <class T>
  void pod(T value) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* p = reinterpret_cast<const std::uint8_t*>(&value);
    bytes.insert(bytes.end(), p, p + sizeof value);
  }
  void text(std::string_view value) {
    pod(static_cast<std::uint64_t>(value.size()));
    bytes.insert(bytes.end(), value.begin(), value.end());
  }
  std::vector<std::uint8_t> bytes;
};

class JobReader {
 public:
  explicit JobReader(const std::vector<std::uint8_t>& bytes) : bytes_(bytes) {}
  template <class T>
  T pod() {
    static_assert(std::is_trivially_copyable_v<T>);
    T value;
    take(&value, sizeof value);
    return value;
  }
  std::string text() {
    const auto size = pod<std::uint64_t>();
    if (size > bytes_.size() - at_) throw JobCodecError("render job: truncated");
    std::string value(static_cast<std::size_t>(size), '\0');
    take(value.data(), value.size());
    return value;
  }
  // A bool or an enum of `limit` + 1 values, read as a byte and checked: never a value its type cannot hold.
  std::uint8_t small(std::uint8_t limit) {
    const auto value = pod<std::uint8_t>();
    if (value > limit) throw JobCodecError("render job: a value out of range");
    return value;
  }
  std::size_t count(std::size_t minItemBytes) {
    const auto n = pod<std::uint64_t>();
    if (n > (bytes_.size() - at_) / minItemBytes) throw JobCodecError("render job: truncated");
    return static_cast<std::size_t>(n);
  }
  void end() const {
    if (at_ != bytes_.size()) throw JobCodecError("render job: trailing bytes");
  }

 private:
  void take(void* out, std::size_t size) {
    if (size > bytes_.size() - at_) throw JobCodecError("render job: truncated");
    if (size) std::memcpy(out, bytes_.data() + at_, size);
    at_ += size;
  }
  const std::vector<std::uint8_t>& bytes_;
  std::size_t at_ = 0;
};

void writeOpenOptions(JobWriter& w, const SceneOpenOptions& o) {
  w.pod(static_cast<std::uint8_t>(o.strict));
  w.pod(o.camera);
  w.pod(static_cast<std::uint8_t>(o.model.up));
  w.pod(o.model.width);
  w.pod(o.model.height);
  w.pod(static_cast<std::uint8_t>(o.model.camera));
  w.pod(static_cast<std::uint8_t>(o.model.lights));
  w.pod(static_cast<std::uint8_t>(o.memory));
  w.pod(static_cast<std::uint8_t>(o.loadTexture));
}

SceneOpenOptions readOpenOptions(JobReader& r) {
  SceneOpenOptions o;
  o.strict = r.small(1) != 0;
  o.camera = r.pod<int>();
  o.model.up = static_cast<ModelUpAxis>(r.small(static_cast<std::uint8_t>(ModelUpAxis::Z)));
  o.model.width = r.pod<int>();
  o.model.height = r.pod<int>();
  o.model.camera = static_cast<ModelViewSource>(r.small(static_cast<std::uint8_t>(ModelViewSource::Rayview)));
  o.model.lights = static_cast<ModelViewSource>(r.small(static_cast<std::uint8_t>(ModelViewSource::Rayview)));
  o.memory = static_cast<MemoryUse>(r.small(static_cast<std::uint8_t>(MemoryUse::Lean)));
  o.loadTexture = r.small(1) != 0;
  return o;
}

}  // namespace

std::vector<std::uint8_t> encodeRenderJob(const RenderJob& job) {
  JobWriter w;
  w.pod(kJobMagic);
  w.pod(static_cast<std::uint64_t>(job.scenes.size()));
  for (const std::string& scene : job.scenes) w.text(scene);
  writeOpenOptions(w, job.open);
  w.pod(static_cast<std::uint64_t>(job.knobs.size()));
  for (const KnobAssignment& k : job.knobs) {
    w.text(k.knob->name);
    w.pod(k.value);
  }
  w.text(job.output.string());
  w.pod(job.turntableFrames);
  w.pod(static_cast<std::uint8_t>(job.overwrite));
  w.pod(static_cast<std::uint8_t>(job.quiet));
  w.pod(job.threads);
  return std::move(w.bytes);
}

RenderJob decodeRenderJob(const std::vector<std::uint8_t>& bytes) {
  JobReader r(bytes);
  if (r.pod<std::uint32_t>() != kJobMagic) throw JobCodecError("render job: not one of this build's");
  RenderJob job;
  job.scenes.resize(r.count(sizeof(std::uint64_t)));
  for (std::string& scene : job.scenes) scene = r.text();
  job.open = readOpenOptions(r);
  job.knobs.resize(r.count(sizeof(std::uint64_t) + sizeof(int)));
  for (KnobAssignment& k : job.knobs) {
    const std::string name = r.text();
    k.knob = findKnob(name);
    if (!k.knob) throw JobCodecError("render job: unknown knob '" + name + "'");
    k.value = r.pod<int>();
  }
  job.output = r.text();
  job.turntableFrames = r.pod<int>();
  job.overwrite = r.small(1) != 0;
  job.quiet = r.small(1) != 0;
  job.threads = r.pod<int>();
  r.end();
  return job;
}

}  // namespace rayview
