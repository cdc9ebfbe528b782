#include "embree_library.h"

#include <dlfcn.h>

#include <type_traits>

namespace rayview {
namespace {

#ifdef RAYVIEW_EMBREE_LINKED
// Sanitizer builds link Embree (renderer/CMakeLists.txt): one reference keeps the linker from dropping it, and the
// dlopen below then returns the library already loaded.
[[maybe_unused]] const volatile auto kLinkedEmbree = &::rtcNewDevice;
#endif

struct Loaded {
  EmbreeLibrary functions{};
  bool ok = false;
  std::string why;
};

Loaded load() {
  Loaded result;
  // RAYVIEW_EMBREE_LIBRARY: the soname CMake found (libembree3.so.3 on Debian 12). RTLD_GLOBAL, as if it had
  // been linked: with RTLD_LOCAL, car's render at 2 threads was 3-5 % slower in four runs of 11-21 pairs (the
  // cause not found), with RTLD_GLOBAL as fast as linked (docs/PERFORMANCE.md, "Embree loaded on first use").
  void* handle = ::dlopen(RAYVIEW_EMBREE_LIBRARY, RTLD_NOW | RTLD_GLOBAL);
  if (!handle) {
    const char* error = ::dlerror();
    result.why = error ? error : "cannot load " RAYVIEW_EMBREE_LIBRARY;
    return result;
  }
  bool complete = true;
  auto find = [&](auto& function, const char* name) {
    function = reinterpret_cast<std::remove_reference_t<decltype(function)>>(::dlsym(handle, name));
    if (!function && complete) {
      complete = false;
      result.why = std::string(RAYVIEW_EMBREE_LIBRARY " has no ") + name;
    }
  };
  EmbreeLibrary& f = result.functions;
  find(f.NewDevice, "rtcNewDevice");
  find(f.SetDeviceErrorFunction, "rtcSetDeviceErrorFunction");
  find(f.GetDeviceError, "rtcGetDeviceError");
  find(f.NewScene, "rtcNewScene");
  find(f.SetSceneFlags, "rtcSetSceneFlags");
  find(f.SetSceneBuildQuality, "rtcSetSceneBuildQuality");
  find(f.SetSceneProgressMonitorFunction, "rtcSetSceneProgressMonitorFunction");
  find(f.CommitScene, "rtcCommitScene");
  find(f.ReleaseScene, "rtcReleaseScene");
  find(f.NewGeometry, "rtcNewGeometry");
  find(f.SetGeometryUserPrimitiveCount, "rtcSetGeometryUserPrimitiveCount");
  find(f.SetGeometryUserData, "rtcSetGeometryUserData");
  find(f.SetGeometryBoundsFunction, "rtcSetGeometryBoundsFunction");
  find(f.SetGeometryIntersectFunction, "rtcSetGeometryIntersectFunction");
  find(f.SetGeometryOccludedFunction, "rtcSetGeometryOccludedFunction");
  find(f.CommitGeometry, "rtcCommitGeometry");
  find(f.AttachGeometry, "rtcAttachGeometry");
  find(f.ReleaseGeometry, "rtcReleaseGeometry");
  find(f.Intersect1, "rtcIntersect1");
  find(f.Intersect16, "rtcIntersect16");
  find(f.Occluded1, "rtcOccluded1");
  find(f.Occluded16, "rtcOccluded16");
  result.ok = complete;
  return result;
}

}  // namespace

const EmbreeLibrary* embreeLibrary(std::string* why) {
  static const Loaded library = load();  // never unloaded: Embree's task scheduler threads outlive any scene
  if (!library.ok && why) *why = library.why;
  return library.ok ? &library.functions : nullptr;
}

}  // namespace rayview
