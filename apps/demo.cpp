// plantarch demo: builds a hand-made plant that shows the model's conventions (a spiral main
// stem, an alternate branch with compound leaves, an opposite decussate branch, flowers and
// fruit) and writes it as OBJ and PNG with a one-paragraph summary.

#include <fmt/format.h>

#include <cstdio>
#include <filesystem>

#include "cli.h"
#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"

namespace plantarch::cli {

namespace {

ShootParameters demoShootTypes(PlantArchitecture& arch) {
    ShootParameters spiral;
    auto& sp = spiral.phytomer_parameters;
    sp.internode.pitch = 4.0f;
    sp.internode.phyllotactic_angle = 137.5f;
    sp.internode.color = {0.35f, 0.45f, 0.2f};
    sp.internode.radial_subdivisions = 10;
    sp.internode.length_segments = 2;
    sp.petiole.pitch = RandomFloat::uniform(50, 70);
    sp.petiole.length = 0.05f;
    sp.petiole.radius = 0.0015f;
    sp.petiole.curvature = -150.0f;
    sp.petiole.taper = 0.6f;
    sp.petiole.length_segments = 5;
    sp.leaf.prototype_scale = RandomFloat::uniform(0.08f, 0.1f);
    sp.leaf.pitch = RandomFloat::uniform(-10, 10);
    sp.leaf.prototype.shape = LeafShape::Ovate;
    sp.leaf.prototype.leaf_aspect_ratio = 0.55f;
    sp.leaf.prototype.serrations = 14;
    sp.leaf.prototype.serration_depth = 0.015f;
    sp.leaf.prototype.midrib_fold_fraction = 0.15f;
    sp.leaf.prototype.longitudinal_curvature = RandomFloat::uniform(-0.3f, -0.1f);
    sp.leaf.prototype.subdivisions = 6;
    sp.peduncle.length = 0.04f;
    sp.peduncle.radius = 0.0008f;
    sp.peduncle.pitch = 40.0f;
    sp.peduncle.curvature = -300.0f;
    sp.peduncle.color = {0.3f, 0.45f, 0.15f};
    sp.inflorescence.flowers_per_peduncle = 3;
    sp.inflorescence.flower_offset = 0.3f;
    sp.inflorescence.pitch = 40.0f;
    sp.inflorescence.flower_prototype_scale = 0.025f;
    sp.inflorescence.fruit_prototype_scale = 0.035f;
    sp.inflorescence.fruit_gravity_factor_fraction = 0.8f;
    spiral.insertion_angle_tip = 40.0f;
    spiral.insertion_angle_decay_rate = 5.0f;
    arch.defineShootType("spiral", spiral);

    ShootParameters alternate = spiral;
    auto& ap = alternate.phytomer_parameters;
    ap.internode.phyllotactic_angle = 180.0f;
    ap.internode.pitch = 10.0f;
    ap.petiole.length = 0.09f;
    ap.petiole.curvature = -100.0f;
    ap.leaf.leaves_per_petiole = 5;
    ap.leaf.leaflet_offset = 0.28f;
    ap.leaf.leaflet_scale = 0.8f;
    ap.leaf.yaw = 15.0f;
    ap.leaf.prototype_scale = RandomFloat::uniform(0.05f, 0.06f);
    ap.leaf.prototype.shape = LeafShape::Elliptic;
    ap.leaf.prototype.leaf_aspect_ratio = 0.5f;
    alternate.gravitropic_curvature = 150.0f;
    arch.defineShootType("alternate", alternate);

    ShootParameters opposite = spiral;
    auto& op = opposite.phytomer_parameters;
    op.petiole.petioles_per_internode = 2;
    op.internode.phyllotactic_angle = 90.0f;
    op.internode.pitch = 0.0f;
    op.petiole.length = 0.025f;
    op.leaf.prototype_scale = RandomFloat::uniform(0.06f, 0.07f);
    op.leaf.prototype.shape = LeafShape::Lanceolate;
    op.leaf.prototype.leaf_aspect_ratio = 0.25f;
    opposite.gravitropic_curvature = 200.0f;
    arch.defineShootType("opposite", opposite);
    return spiral;
}

// Builds the demo plant at `base` and returns its ID.
unsigned buildDemoPlant(PlantArchitecture& arch, const vec3& base) {
    const unsigned plant = arch.addPlantInstance(base, 40.0f);
    ShootSpec stem;
    stem.phytomers = 9;
    stem.size.internodeRadius = 0.005f;
    stem.size.internodeLengthMax = 0.06f;
    stem.radiusTaper = 0.6f;
    stem.shootType = "spiral";
    arch.addBaseStemShoot(plant, stem);

    ShootSpec branch;
    branch.phytomers = 5;
    branch.size.internodeRadius = 0.003f;
    branch.size.internodeLengthMax = 0.045f;
    branch.radiusTaper = 0.5f;
    // Branches placed by hand start at the pitch given: the types' insertion angle (40 at the
    // tip, 5 more per node below it) on the 9-node stem.
    branch.shootType = "alternate";
    branch.baseRotation.pitch = 70.0f;
    arch.addChildShoot(plant, 0u, 2u, branch);
    branch.shootType = "opposite";
    branch.phytomers = 4;
    branch.baseRotation.pitch = 60.0f;
    arch.addChildShoot(plant, 0u, 4u, branch);
    branch.shootType = "alternate";
    branch.phytomers = 3;
    branch.baseRotation.pitch = 50.0f;
    arch.addChildShoot(plant, 0u, 6u, branch);

    arch.addFloralBud(plant, 0, 7, FloralStage::FlowerOpen);
    arch.addFloralBud(plant, 0, 8, FloralStage::FlowerClosed);
    arch.addFloralBud(plant, 0, 5, FloralStage::Fruit);
    return plant;
}

std::function<int()> setupDemo(CLI::App& app, GlobalOptions& global) {
    app.description("Build a hand-made demonstration plant and write it as OBJ and PNG");
    auto out = std::make_shared<std::string>("out");
    app.add_option("-o,--output", *out, "Output directory (created if missing)");
    return [out, &global]() {
        const std::string obj = (std::filesystem::path(*out) / "demo.obj").string();
        const std::string png = (std::filesystem::path(*out) / "demo.png").string();
        CommandOutputs outputs({obj, png});
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.setSeed(global.seed);
        arch.setTriangleLimit(global.maxTriangles);
        arch.setMeshDetail(global.meshDetail);
        demoShootTypes(arch);
        const unsigned plant = buildDemoPlant(arch, {0, 0, 0});
        writeSceneFile(ctx, obj, plantFileOptions(global));
        writeSceneFile(ctx, png, plantFileOptions(global));
        outputs.commit();
        std::printf(
            "%s", fmt::format("Demo plant (seed {}): {} shoots, {} leaves (leaflets counted), "
                              "{:.3f} m^2 one-sided leaf area, {:.3f} m tall, {} objects and {} "
                              "triangles; written to {} and {}.\n",
                              global.seed, arch.getShootCount(plant), arch.getPlantLeafCount(plant),
                              arch.getPlantLeafArea(plant), arch.getPlantHeight(plant),
                              ctx.objectCount(), ctx.triangleCount(), obj, png)
                      .c_str());
        return 0;
    };
}

}  // namespace

PLANTARCH_REGISTER_COMMAND(demo, "demo", 10, setupDemo);

}  // namespace plantarch::cli
