// The picture of procedural textures for docs/formats.md: a bean at 40 days drawn by the
// preview renderer with flat colours and with --materials textured, side by side, and a close
// view of its leaves. With PLANTARCH_WRITE_DOCS_IMAGES=1 it is written full size into
// docs/images/textured-plant.png; otherwise rendered small as a check that the pipeline runs.

#include <gtest/gtest.h>

#include <algorithm>

#include "docs_images.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/Render.h"

using namespace plantarch;

TEST(DocsImages, TexturedPlant) {
    const bool writing = plantarch::testing::writingDocsImages();
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.setSeed(3);
    arch.loadPlantModelFromLibrary("bean");
    arch.buildPlantInstanceFromLibrary(vec3(0.0f), 40.0f);

    RenderOptions o;
    o.width = writing ? 480 : 96;
    o.height = writing ? 560 : 112;
    o.samplesPerPixel = writing ? 16 : 1;
    o.camera.autoFrame = false;
    const AABB box = ctx.boundingBox();
    o.camera.target = box.center();
    o.camera.eye = box.center() + vec3(1.5f, -2.1f, 1.2f) * std::max(box.extent().z, 0.3f);
    o.camera.fovDeg = 32.0f;
    std::vector<Image> panels;
    panels.push_back(render(ctx, o));  // flat
    o.scene.appearance = {MaterialStyle::Textured, 1024};
    panels.push_back(render(ctx, o));
    // Close: the upper leaves from above, at a third of the distance.
    o.camera.target = box.center() + vec3(0.0f, 0.0f, 0.3f * box.extent().z);
    o.camera.eye = o.camera.target + vec3(0.25f, -0.35f, 0.45f) * std::max(box.extent().z, 0.3f);
    panels.push_back(render(ctx, o));
    EXPECT_NE(panels[0].rgb, panels[1].rgb);
    if (writing)
        writePNG(plantarch::testing::strip(panels),
                 plantarch::testing::docsImagePath("textured-plant.png"));
}
