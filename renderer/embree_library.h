#pragma once
// Private: Embree 3's functions, loaded from its shared library (dlopen) when a scene first needs Embree, not at
// every process start. Linked the ordinary way, libembree3 and the libtbb it needs cost every process 2.0-2.8 ms
// before main (Debian links both with BIND_NOW; libembree3 runs 168 static initialisers), and the scenes of up to
// kPacketBvhTriangles triangles never use it: they get rayview's packet BVH (docs/PERFORMANCE.md, "Embree
// loaded on first use").

#include <string>

#include <embree3/rtcore.h>

namespace rayview {

// The functions the Embree back-end calls, by the names of rtcore.h without the `rtc` prefix.
struct EmbreeLibrary {
  decltype(&::rtcNewDevice) NewDevice;
  decltype(&::rtcSetDeviceErrorFunction) SetDeviceErrorFunction;
  decltype(&::rtcGetDeviceError) GetDeviceError;
  decltype(&::rtcNewScene) NewScene;
  decltype(&::rtcSetSceneFlags) SetSceneFlags;
  decltype(&::rtcSetSceneBuildQuality) SetSceneBuildQuality;
  decltype(&::rtcSetSceneProgressMonitorFunction) SetSceneProgressMonitorFunction;
  decltype(&::rtcCommitScene) CommitScene;
  decltype(&::rtcReleaseScene) ReleaseScene;
  decltype(&::rtcNewGeometry) NewGeometry;
  decltype(&::rtcSetGeometryUserPrimitiveCount) SetGeometryUserPrimitiveCount;
  decltype(&::rtcSetGeometryUserData) SetGeometryUserData;
  decltype(&::rtcSetGeometryBoundsFunction) SetGeometryBoundsFunction;
  decltype(&::rtcSetGeometryIntersectFunction) SetGeometryIntersectFunction;
  decltype(&::rtcSetGeometryOccludedFunction) SetGeometryOccludedFunction;
  decltype(&::rtcCommitGeometry) CommitGeometry;
  decltype(&::rtcAttachGeometry) AttachGeometry;
  decltype(&::rtcReleaseGeometry) ReleaseGeometry;
  decltype(&::rtcIntersect1) Intersect1;
  decltype(&::rtcIntersect16) Intersect16;
  decltype(&::rtcOccluded1) Occluded1;
  decltype(&::rtcOccluded16) Occluded16;
};

// The library, loaded on the first call (from any thread; later calls return the same), or nullptr when it cannot
// be loaded or lacks a function: then *why (when given) says why.
const EmbreeLibrary* embreeLibrary(std::string* why = nullptr);

}  // namespace rayview
