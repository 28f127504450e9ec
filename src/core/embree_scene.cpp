// The process's Embree device and scenes of triangles (embree_scene.h).

#include "core/embree_scene.h"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <stdexcept>
#include <string>

namespace plantarch::core {

namespace {

std::atomic<int> devicesMade{0};

RTCDevice makeDevice() {
    const std::string config = "threads=" + std::to_string(std::max(1, omp_get_max_threads()));
    RTCDevice device = embree().rtcNewDevice(config.c_str());
    if (!device) throw std::runtime_error("cannot create an Embree device");
    devicesMade.fetch_add(1, std::memory_order_relaxed);
    return device;
}

}  // namespace

RTCDevice embreeDevice() {
    // Made once (a throwing first call leaves it to the next); never released: scenes made
    // on it may live in objects destroyed at exit, after any owner the device could have.
    static const RTCDevice device = makeDevice();
    return device;
}

int embreeDevicesMade() {
    return devicesMade.load(std::memory_order_relaxed);
}

void throwOnEmbreeError(const char* what) {
    const RTCError err = embree().rtcGetDeviceError(embreeDevice());
    if (err != RTC_ERROR_NONE)
        throw std::runtime_error(std::string("Embree error ") + std::to_string(int(err)) +
                                 " while " + what);
}

TriangleGeometry newTriangleGeometry(std::size_t vertices, std::size_t triangles,
                                     RTCBuildQuality quality) {
    const EmbreeApi& rtc = embree();
    TriangleGeometry g;
    g.geometry = rtc.rtcNewGeometry(embreeDevice(), RTC_GEOMETRY_TYPE_TRIANGLE);
    rtc.rtcSetGeometryBuildQuality(g.geometry, quality);
    g.positions = static_cast<float*>(rtc.rtcSetNewGeometryBuffer(
        g.geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertices));
    g.indices = static_cast<std::uint32_t*>(
        rtc.rtcSetNewGeometryBuffer(g.geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                    3 * sizeof(std::uint32_t), triangles));
    return g;
}

RTCScene newScene(RTCBuildQuality quality, RTCSceneFlags flags) {
    const EmbreeApi& rtc = embree();
    RTCScene scene = rtc.rtcNewScene(embreeDevice());
    rtc.rtcSetSceneBuildQuality(scene, quality);
    if (flags != RTC_SCENE_FLAG_NONE) rtc.rtcSetSceneFlags(scene, flags);
    return scene;
}

RTCScene triangleScene(const std::vector<vec3>& soup, RTCBuildQuality quality) {
    const EmbreeApi& rtc = embree();
    RTCScene scene = newScene(quality);
    if (!soup.empty()) {
        const std::size_t n = soup.size();
        const TriangleGeometry g = newTriangleGeometry(n, n / 3, quality);
        for (std::size_t i = 0; i < n; ++i) {
            g.positions[3 * i + 0] = soup[i].x;
            g.positions[3 * i + 1] = soup[i].y;
            g.positions[3 * i + 2] = soup[i].z;
            g.indices[i] = std::uint32_t(i);
        }
        rtc.rtcCommitGeometry(g.geometry);
        rtc.rtcAttachGeometryByID(scene, g.geometry, 0);
        rtc.rtcReleaseGeometry(g.geometry);
    }
    rtc.rtcCommitScene(scene);
    return scene;
}

}  // namespace plantarch::core
