// Pictures of the labelled outputs for docs/formats.md: a bean shaded, its instance mask and
// its depth image; its surface samples and a two-scanner scan drawn as points in their organ
// colours. With PLANTARCH_WRITE_DOCS_IMAGES=1 they are written full size into docs/images/;
// otherwise the same pictures are made small, as a check that each shows what it should.

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <set>

#include "docs_images.h"
#include "plantarch/Export.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/Render.h"
#include "plantarch/Scan.h"

using namespace plantarch;

namespace {

using plantarch::testing::strip;
const auto writing = plantarch::testing::writingDocsImages;
const auto docsPath = plantarch::testing::docsImagePath;

// Points as small squares facing the eye, one object per organ kind carrying its label, so
// the renderer's organ mode draws them in the organ colours.
Context splats(const PointCloud& cloud, const vec3& eye, float size) {
    std::vector<Mesh> meshes(kOrganLabels.size());
    for (std::size_t i = 0; i < cloud.positions.size(); ++i) {
        const vec3 p = cloud.positions[i];
        const vec3 view = glm::normalize(eye - p);
        const vec3 side = glm::normalize(glm::cross(view, vec3(0, 0, 1))) * (size / 2);
        const vec3 up = glm::cross(side, view);
        Mesh& m = meshes[cloud.organ[i]];
        const auto first = std::uint32_t(m.positions.size());
        m.positions.insert(m.positions.end(),
                           {p - side - up, p + side - up, p + side + up, p - side + up});
        m.indices.insert(m.indices.end(),
                         {first, first + 1, first + 2, first, first + 2, first + 3});
    }
    Context ctx;
    for (std::size_t k = 0; k < meshes.size(); ++k) {
        if (meshes[k].positions.empty()) continue;
        const ObjectID id = ctx.addObject(meshes[k], Material{});
        ctx.setObjectData(id, "organ", std::string(kOrganLabels[k]));
    }
    return ctx;
}

std::size_t litPixels(const Image& image) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < image.rgb.size(); i += 3)
        n += (image.rgb[i] | image.rgb[i + 1] | image.rgb[i + 2]) != 0;
    return n;
}

}  // namespace

TEST(DocsImages, LabelledPicturesAndPointClouds) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.setSeed(3);
    arch.loadPlantModelFromLibrary("bean");
    arch.buildPlantInstanceFromLibrary(vec3(0.0f), 40);
    RenderOptions o;
    o.width = writing() ? 480 : 96;
    o.height = writing() ? 420 : 84;
    o.samplesPerPixel = writing() ? 16 : 1;
    o.groundPlane = false;
    // One camera for every panel: the one framing the plant.
    const RenderScene scene(ctx);
    const CameraFrame frame = scene.camera(o);
    o.camera.autoFrame = false;
    o.camera.eye = frame.eye;
    o.camera.target = frame.target;
    o.camera.up = frame.up;
    o.camera.fovDeg = frame.fovDeg;

    const Image shaded = scene.render(o);
    RenderOptions labels = o;
    labels.mode = RenderMode::LabelObject;
    const Image instances = scene.render(labels);
    const Image depth = depthPicture(scene.renderDepth(o));
    // Every pixel that sees the plant has a distance and an instance; many instances show.
    EXPECT_EQ(litPixels(instances), litPixels(depth));
    std::set<ObjectID> seen;
    for (int y = 0; y < instances.height; ++y)
        for (int x = 0; x < instances.width; ++x)
            if (auto id = objectIDFromLabelColor(instances.pixel(x, y))) seen.insert(*id);
    EXPECT_GT(seen.size(), 20u);

    labels.mode = RenderMode::LabelOrgan;
    const float splat = writing() ? 0.003f : 0.01f;
    const PointCloud samples = samplePoints(ctx, {.points = writing() ? 60000u : 6000u, .seed = 3});
    ScanOptions so;
    for (const vec3& at : {vec3(0.9f, -0.5f, 0.6f), vec3(-0.8f, 0.6f, 0.6f)}) {
        Scanner s;
        s.origin = at;
        s.resolution = writing() ? 0.35f : 0.7f;
        s.zenithMin = 45.0f;
        s.zenithMax = 150.0f;
        so.scanners.push_back(s);
    }
    so.rangeNoise = 0.002f;
    const PointCloud scanned = scan(ctx, so);
    EXPECT_GT(scanned.positions.size(), 1000u);
    const Image samplePicture = render(splats(samples, o.camera.eye, splat), labels);
    const Image scanPicture = render(splats(scanned, o.camera.eye, splat), labels);
    EXPECT_GT(litPixels(samplePicture), litPixels(instances) / 10);
    EXPECT_GT(litPixels(scanPicture), litPixels(instances) / 10);
    if (writing()) {
        writePNG(strip({shaded, instances, depth}), docsPath("labelled-pictures.png"));
        writePNG(strip({samplePicture, scanPicture}), docsPath("point-clouds.png"));
    }
}
