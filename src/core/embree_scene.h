#pragma once
// The Embree device of the process and what rendering, scans and collision avoidance all do
// with it: triangle geometries, scenes of triangles, rays. Embree itself is loaded when the
// device is first asked for (embree_api.h), so a process that casts no ray never loads it.

#include <embree3/rtcore.h>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/embree_api.h"
#include "plantarch/Mesh.h"

namespace plantarch::core {

/// The process's one Embree device: made on the first call (loading Embree), by one thread
/// when several ask at once, and kept for the life of the process. Its worker threads are as
/// many as OpenMP's at that first call. Throws plantarch::Error when Embree cannot be loaded,
/// std::runtime_error when the device cannot be made; a later call tries again.
RTCDevice embreeDevice();

/// How many Embree devices the process has made (0 until the first embreeDevice(), then 1).
int embreeDevicesMade();

/// Throws std::runtime_error ("Embree error N while WHAT") when the device reports an error
/// on the calling thread.
void throwOnEmbreeError(const char* what);

/// A new triangle geometry and its buffers, which the caller fills and then commits:
/// `positions` holds xyz per vertex, `indices` three vertex indices per triangle.
struct TriangleGeometry {
    RTCGeometry geometry = nullptr;
    float* positions = nullptr;
    std::uint32_t* indices = nullptr;
};
TriangleGeometry newTriangleGeometry(std::size_t vertices, std::size_t triangles,
                                     RTCBuildQuality quality);

/// A new scene, not committed.
RTCScene newScene(RTCBuildQuality quality, RTCSceneFlags flags = RTC_SCENE_FLAG_NONE);

/// A committed scene of the triangles of `soup` (three corners each, primitive i the corners
/// 3i..3i+2) as geometry 0; an empty scene when the soup is empty.
RTCScene triangleScene(const std::vector<vec3>& soup, RTCBuildQuality quality);

/// A ray from `origin` along `direction` over [tnear, tfar], with no hit yet, for
/// rtcIntersect1 (its `ray` alone for rtcOccluded1).
inline RTCRayHit rayHit(const vec3& origin, const vec3& direction, float tnear, float tfar) {
    RTCRayHit rh;
    rh.ray.org_x = origin.x;
    rh.ray.org_y = origin.y;
    rh.ray.org_z = origin.z;
    rh.ray.tnear = tnear;
    rh.ray.dir_x = direction.x;
    rh.ray.dir_y = direction.y;
    rh.ray.dir_z = direction.z;
    rh.ray.time = 0.0f;
    rh.ray.tfar = tfar;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    return rh;
}

}  // namespace plantarch::core
