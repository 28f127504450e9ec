// Pictures for the docs: a growth time-lapse and a hand-built plant. With
// PLANTARCH_WRITE_DOCS_IMAGES=1 they are written full size into docs/images/; otherwise the
// same scenes are built and rendered small as a check that the pipeline runs.

#include "docs_images.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>

#include "plantarch/PlantArchitecture.h"
#include "plantarch/Render.h"

using namespace plantarch;

namespace {

using plantarch::testing::strip;
const auto writing = plantarch::testing::writingDocsImages;
const auto docsPath = plantarch::testing::docsImagePath;

ShootParameters timelapseShoot() {
    ShootParameters s;
    auto& p = s.phytomer_parameters;
    p.internode.pitch = 8.0f;
    p.internode.phyllotactic_angle = RandomFloat::uniform(150, 210);
    p.internode.radius_initial = 0.0015f;
    p.internode.color = {0.33f, 0.42f, 0.16f};
    p.internode.max_floral_buds_per_petiole = 1;
    p.internode.radial_subdivisions = 10;
    p.petiole.pitch = RandomFloat::uniform(35, 55);
    p.petiole.length = RandomFloat::uniform(0.08f, 0.11f);
    p.petiole.radius = 0.0012f;
    p.petiole.curvature = RandomFloat::uniform(-150, 50);
    p.petiole.taper = 0.5f;
    p.petiole.length_segments = 5;
    p.leaf.leaves_per_petiole = 3;
    p.leaf.leaflet_offset = 0.3f;
    p.leaf.leaflet_scale = 0.9f;
    p.leaf.yaw = 15.0f;
    p.leaf.pitch = RandomFloat::normal(0, 12);
    p.leaf.prototype_scale = RandomFloat::uniform(0.07f, 0.09f);
    p.leaf.prototype.shape = LeafShape::Ovate;
    p.leaf.prototype.leaf_aspect_ratio = 0.7f;
    p.leaf.prototype.midrib_fold_fraction = 0.2f;
    p.leaf.prototype.lateral_curvature = -0.8f;
    p.leaf.prototype.subdivisions = 5;
    p.peduncle.length = 0.05f;
    p.peduncle.radius = 0.0008f;
    p.peduncle.pitch = 30.0f;
    p.peduncle.curvature = -200.0f;
    p.inflorescence.flowers_per_peduncle = RandomInt::uniform(1, 3);
    p.inflorescence.flower_offset = 0.25f;
    p.inflorescence.pitch = 50.0f;
    p.inflorescence.flower_prototype_scale = 0.02f;
    p.inflorescence.fruit_prototype_scale = RandomFloat::uniform(0.035f, 0.045f);
    p.inflorescence.fruit_gravity_factor_fraction = 0.9f;
    p.inflorescence.fruit_color = {0.35f, 0.55f, 0.15f};
    s.max_nodes = 14;
    s.phyllochron_min = 2.5f;
    s.elongation_rate_max = 0.12f;
    s.internode_length_max = 0.035f;
    s.gravitropic_curvature = 150.0f;
    s.girth_area_factor = 2.0f;
    s.insertion_angle_tip = RandomFloat::uniform(40, 55);
    s.vegetative_bud_break_probability_min = 0.1f;
    s.vegetative_bud_break_probability_decay_rate = -0.4f;
    s.vegetative_bud_break_time = 10.0f;
    s.flower_bud_break_probability = 0.5f;
    s.fruit_set_probability = 0.6f;
    s.determinate_shoot_growth = false;
    return s;
}

}  // namespace

TEST(DocsImages, GrowthTimeLapse) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    PhenologyParameters ph;
    ph.time_to_flower_initiation = 22;
    ph.time_to_flower_opening = 4;
    ph.time_to_fruit_set = 5;
    ph.time_to_fruit_maturity = 12;
    arch.setDefaultPhenology(ph);
    arch.defineShootType("main", timelapseShoot());
    const unsigned p = arch.addPlantInstance(vec3(0.0f), 0.0f);
    arch.addBaseStemShoot(p, {1, {}, {0.0015f, 0.035f, 0.05f, 0.05f}, 0.0f, "main"});
    RenderOptions o;
    o.width = writing() ? 480 : 96;
    o.height = writing() ? 600 : 120;
    o.samplesPerPixel = writing() ? 16 : 1;
    o.camera.autoFrame = false;
    o.camera.eye = {1.3f, -1.55f, 0.9f};
    o.camera.target = {0.0f, 0.0f, 0.3f};
    o.camera.fovDeg = 24.0f;
    std::vector<Image> frames;
    float lastHeight = 0.0f;
    for (int day : {10, 20, 30, 40}) {
        arch.advanceTime(double(day) - arch.getPlantAge(p));
        EXPECT_GT(arch.getPlantHeight(p), lastHeight) << "day " << day;
        lastHeight = arch.getPlantHeight(p);
        frames.push_back(render(ctx, o));
    }
    EXPECT_GT(arch.getPlantObjectIDs(p, OrganKind::Fruit).size(), 0u);
    const Image out = strip(frames);
    EXPECT_NE(frames[0].rgb, frames[3].rgb);
    if (writing()) writePNG(out, docsPath("growth-timelapse.png"));
}

TEST(DocsImages, RenderReportsProgressAndBandsDoNotChangePixels) {
    Context ctx;
    Mesh quad;
    quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.5f}, {0, 1, 0.5f}};
    quad.indices = {0, 1, 2, 0, 2, 3};
    ctx.addObject(quad, Material{{0.2f, 0.6f, 0.2f}});
    RenderOptions o;
    o.width = 64;
    o.height = 150;  // three bands of 64, 64 and 22 rows
    o.samplesPerPixel = 1;
    const Image quiet = render(ctx, o);
    std::vector<double> fractions;
    o.progress = [&](std::string_view stage, double f) {
        EXPECT_EQ(stage, "rendering");
        fractions.push_back(f);
    };
    const Image reported = render(ctx, o);
    EXPECT_EQ(quiet.rgb, reported.rgb);
    ASSERT_EQ(fractions.size(), 3u);
    EXPECT_DOUBLE_EQ(fractions.back(), 1.0);
    EXPECT_LT(fractions.front(), fractions[1]);
}
