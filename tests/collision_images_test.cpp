// Pictures for docs/collision.md: a bean beside a wall, vines on a trellis wire, a dense bean
// canopy without and with soft avoidance. With PLANTARCH_WRITE_DOCS_IMAGES=1 they are written
// full size into docs/images/; otherwise the same scenes are built and rendered small.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>

#include "collision/intersections.h"
#include "collision_scenes.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/Render.h"

using namespace plantarch;
using namespace plantarch::test;

namespace {

bool writing() {
    return std::getenv("PLANTARCH_WRITE_DOCS_IMAGES") != nullptr;
}

std::string docsPath(const std::string& name) {
    return std::string(PLANTARCH_SOURCE_DIR) + "/docs/images/" + name;
}

// Images side by side with a white gap.
Image sideBySide(const std::vector<Image>& frames, int gap = 8) {
    int width = -gap;
    for (const Image& f : frames) width += f.width + gap;
    Image out(width, frames.front().height);
    std::fill(out.rgb.begin(), out.rgb.end(), 255);
    int x0 = 0;
    for (const Image& f : frames) {
        for (int y = 0; y < f.height; ++y)
            std::memcpy(&out.rgb[(std::size_t(y) * out.width + std::size_t(x0)) * 3],
                        &f.rgb[std::size_t(y) * f.width * 3], std::size_t(f.width) * 3);
        x0 += f.width + gap;
    }
    return out;
}

RenderOptions options(int w, int h) {
    RenderOptions o;
    o.width = writing() ? w : w / 8;
    o.height = writing() ? h : h / 8;
    o.samplesPerPixel = writing() ? 16 : 1;
    o.camera.autoFrame = false;
    return o;
}

}  // namespace

TEST(CollisionImages, BeanBesideAWall) {
    std::vector<Image> frames;
    for (bool avoid : {false, true}) {
        Context ctx;
        PlantArchitecture arch(&ctx);
        const ObjectID wall =
            addBox(ctx, {0.12f, -0.45f, 0.0f}, {0.135f, 0.45f, 0.75f}, vec3(0.78f, 0.74f, 0.68f));
        arch.loadPlantModelFromLibrary("bean");
        if (avoid)
            arch.enableSolidObstacleAvoidance({.obstacles = {wall}, .avoidanceDistance = 0.2f});
        const unsigned p = arch.buildPlantInstanceFromLibrary({0, 0, 0}, 50.0f);
        const float maxX = extreme(ctx, arch, p, 0, true);
        if (avoid)
            EXPECT_LE(maxX, 0.12f);
        else
            EXPECT_GT(maxX, 0.2f);
        RenderOptions o = options(560, 640);
        o.camera.eye = {0.12f, -1.35f, 1.15f};
        o.camera.target = {0.06f, 0.0f, 0.25f};
        o.camera.fovDeg = 30.0f;
        frames.push_back(render(ctx, o));
    }
    if (writing()) writePNG(sideBySide(frames), docsPath("collision-wall.png"));
}

TEST(CollisionImages, VinesOnATrellisWire) {
    std::vector<Image> frames;
    for (bool wire : {false, true}) {
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.setSeed(3);
        arch.loadPlantModelFromLibrary(speciesFile("vine_picture", vine(wire, 28)));
        for (int i = 0; i < 3; ++i) {
            const float x = 1.2f * float(i);
            addBox(ctx, {x - 0.06f, -0.02f, 0.0f}, {x - 0.02f, 0.02f, 0.62f},
                   vec3(0.45f, 0.33f, 0.2f));
            const unsigned p = arch.buildPlantInstanceFromLibrary({x, 0, 0}, 40.0f);
            // The picture shows what it claims: with the wire each cane (shoot 1) runs along
            // it, 0.5 m up from x + 0.02 on, and reaches well along the row; without, the
            // cane's tip rises away from where the wire would be.
            const unsigned cane = 1, nodes = arch.getShootNodeCount(p, cane);
            ASSERT_GT(nodes, 10u);
            const vec3 tip = arch.getNodePosition(p, cane, nodes - 1);
            if (wire) {
                for (unsigned k = 0; k < nodes; ++k) {
                    const vec3 q = arch.getNodePosition(p, cane, k);
                    EXPECT_NEAR(q.z, 0.5f, 0.04f) << "vine " << i << " node " << k;
                    EXPECT_NEAR(q.y, 0.0f, 0.04f) << "vine " << i << " node " << k;
                }
                EXPECT_GT(tip.x - x, 0.6f) << "vine " << i;
            } else {
                EXPECT_GT(tip.z, 0.65f) << "vine " << i;
            }
        }
        // The wire itself, 2 mm thick, along the row at its height (0.5 m).
        addBox(ctx, {-0.04f, -0.001f, 0.499f}, {3.6f, 0.001f, 0.501f}, vec3(0.3f));
        RenderOptions o = options(1200, 420);
        o.camera.eye = {1.75f, -3.3f, 1.05f};
        o.camera.target = {1.75f, 0.0f, 0.48f};
        o.camera.fovDeg = 23.0f;
        frames.push_back(render(ctx, o));
    }
    EXPECT_NE(frames[0].rgb, frames[1].rgb);
    if (writing()) {  // one above the other: without, then with the wire's attraction points
        Image out(frames[0].width, frames[0].height * 2 + 8);
        std::fill(out.rgb.begin(), out.rgb.end(), 255);
        std::memcpy(out.rgb.data(), frames[0].rgb.data(), frames[0].rgb.size());
        std::memcpy(&out.rgb[std::size_t(frames[0].height + 8) * out.width * 3],
                    frames[1].rgb.data(), frames[1].rgb.size());
        writePNG(out, docsPath("collision-trellis.png"));
    }
}

TEST(CollisionImages, DenseCanopyWithoutAndWithSoftAvoidance) {
    std::vector<Image> frames;
    for (bool soft : {false, true}) {
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.setSeed(3);
        arch.loadPlantModelFromLibrary("bean");
        if (soft) arch.enableSoftCollisionAvoidance();
        arch.buildPlantCanopyFromLibrary({0, 0, 0}, {0.15f, 0.15f}, {4, 4}, 35.0f);
        RenderOptions o = options(640, 560);
        o.camera.eye = {1.2f, -1.75f, 1.5f};
        o.camera.target = {0.0f, 0.0f, 0.1f};
        o.camera.fovDeg = 30.0f;
        frames.push_back(render(ctx, o));
    }
    EXPECT_NE(frames[0].rgb, frames[1].rgb);
    if (writing()) writePNG(sideBySide(frames), docsPath("collision-canopy.png"));
}

// For docs/species-orchard.md: the fruiting-wall apple at 630 days seen across the row, bare
// wood only, without (left) and with (right) its wires' attraction points; the wires in blue.
TEST(CollisionImages, FruitingWallOnItsWires) {
    std::vector<Image> frames;
    for (bool points : {false, true}) {
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.loadPlantModelFromLibrary("apple_fruitingwall");
        const unsigned p = arch.buildPlantInstanceFromLibrary({0, 0, 0}, 0.0f);
        if (!points) arch.disableAttractionPoints(p);
        arch.advanceTime(630.0);
        const std::vector<ObjectID> wood = arch.getPlantObjectIDs(p, OrganKind::Internode);
        for (ObjectID o : arch.getAllPlantObjectIDs(p))
            if (std::find(wood.begin(), wood.end(), o) == wood.end()) ctx.deleteObject(o);
        for (float z : {0.75f, 1.6f, 2.25f, 2.8f})
            addBox(ctx, {-0.006f, -0.6f, z - 0.006f}, {0.006f, 0.6f, z + 0.006f},
                   vec3(0.15f, 0.3f, 0.9f));
        RenderOptions o = options(560, 720);
        o.camera.eye = {7.0f, 0.0f, 2.0f};
        o.camera.target = {0.0f, 0.0f, 1.95f};
        o.camera.fovDeg = 34.0f;
        frames.push_back(render(ctx, o));
    }
    EXPECT_NE(frames[0].rgb, frames[1].rgb);
    if (writing()) writePNG(sideBySide(frames), docsPath("trellis-apple-fruitingwall.png"));
}
