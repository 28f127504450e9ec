// The one Embree device of a process (core/embree_scene.h): shared by pictures and collision
// avoidance, made once however many threads ask for it, and the scenes and rays made with it.

#include "core/embree_scene.h"

#include <gtest/gtest.h>

#include <thread>
#include <vector>

#include "collision/collision_world.h"
#include "plantarch/Context.h"
#include "plantarch/Render.h"

using namespace plantarch;

namespace {

// One triangle in the plane z = 1 over the unit square's lower-left half.
std::vector<vec3> oneTriangle() {
    return {vec3(0.0f, 0.0f, 1.0f), vec3(1.0f, 0.0f, 1.0f), vec3(0.0f, 1.0f, 1.0f)};
}

}  // namespace

TEST(EmbreeScene, PicturesAndCollisionShareOneDevice) {
    Context ctx;
    const ObjectID wall =
        ctx.addObject(Mesh{.positions = oneTriangle(), .uvs = {}, .indices = {0, 1, 2}});
    RenderOptions o;
    o.width = 16;
    o.height = 12;
    o.samplesPerPixel = 1;
    (void)render(ctx, o);
    {
        collision::World world;
        world.setSolid(SolidObstacleOptions{.obstacles = {wall}}, ctx);
        EXPECT_TRUE(world.solidHit(vec3(0.2f, 0.2f, 0.0f), vec3(0.0f, 0.0f, 1.0f), 0.0f, 5.0f));
    }
    (void)render(ctx, o);
    EXPECT_EQ(core::embreeDevicesMade(), 1);
}

TEST(EmbreeScene, DeviceIsMadeOnceForThreadsAskingTogether) {
    std::vector<RTCDevice> seen(8, nullptr);
    std::vector<std::thread> threads;
    for (std::size_t i = 0; i < seen.size(); ++i)
        threads.emplace_back([&seen, i] { seen[i] = core::embreeDevice(); });
    for (std::thread& t : threads) t.join();
    for (RTCDevice d : seen) EXPECT_EQ(d, seen[0]);
    EXPECT_NE(seen[0], nullptr);
    EXPECT_EQ(core::embreeDevicesMade(), 1);
}

TEST(EmbreeScene, RayHitsTheTrianglesOfAScene) {
    RTCScene scene = core::triangleScene(oneTriangle(), RTC_BUILD_QUALITY_LOW);
    RTCIntersectContext ictx;
    rtcInitIntersectContext(&ictx);
    const vec3 org(0.25f, 0.25f, 0.0f), up(0.0f, 0.0f, 1.0f);

    RTCRayHit hit = core::rayHit(org, up, 0.0f, 10.0f);
    core::embree().rtcIntersect1(scene, &ictx, &hit);
    EXPECT_EQ(hit.hit.geomID, 0u);
    EXPECT_EQ(hit.hit.primID, 0u);
    EXPECT_FLOAT_EQ(hit.ray.tfar, 1.0f);

    // The triangle beyond tfar, before tnear, or off to the side: no hit, tfar kept.
    for (const auto& [from, tnear, tfar] :
         {std::tuple{org, 0.0f, 0.5f}, std::tuple{org, 1.5f, 10.0f},
          std::tuple{vec3(0.75f, 0.75f, 0.0f), 0.0f, 10.0f}}) {
        RTCRayHit miss = core::rayHit(from, up, tnear, tfar);
        core::embree().rtcIntersect1(scene, &ictx, &miss);
        EXPECT_EQ(miss.hit.geomID, RTC_INVALID_GEOMETRY_ID);
        EXPECT_EQ(miss.ray.tfar, tfar);
    }
    core::embree().rtcReleaseScene(scene);

    // An empty soup: a scene that nothing hits.
    RTCScene empty = core::triangleScene({}, RTC_BUILD_QUALITY_LOW);
    RTCRayHit none = core::rayHit(org, up, 0.0f, 10.0f);
    core::embree().rtcIntersect1(empty, &ictx, &none);
    EXPECT_EQ(none.hit.geomID, RTC_INVALID_GEOMETRY_ID);
    core::embree().rtcReleaseScene(empty);
}
