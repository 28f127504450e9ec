#pragma once
// Embree, the ray tracer of collision avoidance, rendering and scans, loaded the first time
// one of them needs it (dlopen) rather than linked: a command or a Python session that draws
// no picture and steers no shoot never maps it. Loading and initialising the library costs
// about 8 ms of CPU, more than a small plant's whole build.
//
// Callers write core::embree().rtcNewDevice(...) where they would call rtcNewDevice(...); the
// types, constants and inline helpers (rtcInitIntersectContext) come from Embree's headers as
// usual. PLANTARCH_EMBREE_LIBRARY names another library file to load (default
// libembree3.so.3, found as the dynamic linker finds libraries).

#include <embree3/rtcore.h>

namespace plantarch::core {

// The Embree functions plantarch calls, each declared once here.
// clang-format off
#define PLANTARCH_EMBREE_FUNCTIONS(X) \
    X(rtcNewDevice) \
    X(rtcReleaseDevice) \
    X(rtcGetDeviceError) \
    X(rtcNewScene) \
    X(rtcReleaseScene) \
    X(rtcSetSceneBuildQuality) \
    X(rtcSetSceneFlags) \
    X(rtcSetSceneProgressMonitorFunction) \
    X(rtcCommitScene) \
    X(rtcNewGeometry) \
    X(rtcReleaseGeometry) \
    X(rtcSetGeometryBuildQuality) \
    X(rtcSetNewGeometryBuffer) \
    X(rtcSetGeometryUserData) \
    X(rtcSetGeometryIntersectFilterFunction) \
    X(rtcSetGeometryOccludedFilterFunction) \
    X(rtcCommitGeometry) \
    X(rtcAttachGeometryByID) \
    X(rtcIntersect1) \
    X(rtcOccluded1) \
    X(rtcPointQuery)
// clang-format on

/// The Embree functions, as pointers into the loaded library.
struct EmbreeApi {
#define PLANTARCH_EMBREE_MEMBER(name) decltype(&::name) name = nullptr;
    PLANTARCH_EMBREE_FUNCTIONS(PLANTARCH_EMBREE_MEMBER)
#undef PLANTARCH_EMBREE_MEMBER
};

/// Embree, loaded on the first call (thread-safe). Throws plantarch::Error naming the library
/// when it cannot be loaded or lacks a function; later calls try again.
const EmbreeApi& embree();

}  // namespace plantarch::core
