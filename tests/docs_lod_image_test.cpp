// The picture of a level-of-detail chain for docs/formats.md: a tomato at full detail, reduced
// by meshoptimizer, as cards, and built at the lowest mesh detail. With
// PLANTARCH_WRITE_DOCS_IMAGES=1 it is written full size into docs/images/lod-chain.png;
// otherwise rendered small as a check that the pipeline runs.

#include <gtest/gtest.h>

#include <utility>

#include "docs_images.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/Render.h"
#include "scene_io/scene_lod.h"

using namespace plantarch;

TEST(DocsImages, LevelOfDetailChain) {
    const bool writing = plantarch::testing::writingDocsImages();
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.setSeed(3);
    arch.loadPlantModelFromLibrary("tomato");
    arch.buildPlantInstanceFromLibrary(vec3(0.0f), 60.0f);
    Context lowest;
    PlantArchitecture coarse(&lowest);
    coarse.setSeed(3);
    coarse.setMeshDetail(0.1f);
    coarse.loadPlantModelFromLibrary("tomato");
    coarse.buildPlantInstanceFromLibrary(vec3(0.0f), 60.0f);

    const Context reduced = io::lodLevel(ctx, {.kind = GltfLevel::Kind::Reduced, .share = 0.25f});
    const Context cards = io::lodLevel(ctx, {.kind = GltfLevel::Kind::Cards});
    EXPECT_LT(reduced.triangleCount(), ctx.triangleCount() / 3);
    EXPECT_LT(cards.triangleCount() * 10, ctx.triangleCount());
    EXPECT_LT(lowest.triangleCount() * 10, ctx.triangleCount());

    RenderOptions o;
    o.width = writing ? 400 : 80;
    o.height = writing ? 560 : 112;
    o.samplesPerPixel = writing ? 16 : 1;
    o.camera.autoFrame = false;
    const AABB box = ctx.boundingBox();
    o.camera.target = box.center();
    o.camera.eye = box.center() + vec3(1.1f, -1.5f, 0.55f) * std::max(box.extent().z, 0.3f);
    o.camera.fovDeg = 30.0f;
    std::vector<Image> panels;
    for (const Context* c : {&std::as_const(ctx), &reduced, &cards, &std::as_const(lowest)})
        panels.push_back(render(*c, o));
    EXPECT_NE(panels[0].rgb, panels[2].rgb);
    if (writing)
        writePNG(plantarch::testing::strip(panels),
                 plantarch::testing::docsImagePath("lod-chain.png"));
}
