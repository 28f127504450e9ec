// plantarch reconstruct SKELETON --species NAME -o OUT [-o OUT ...] [--age A] [--unit cm]
//     [--spacing M] [--leaf-scale F] [--base-type T] [--branch-type T] [--grow DAYS]
// Rebuilds measured plants: each root of a skeleton (.csv node table, .json or .mtg) becomes
// a plant of the species whose internodes run through the measured points, with leaves and
// buds placed by the species; optionally grown on from there.

#include <fmt/format.h>

#include <cstdio>

#include "cli.h"
#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/Skeleton.h"

namespace plantarch::cli {

namespace {

struct ReconstructArgs {
    std::string input, species, unit = "m";
    std::vector<std::string> outputs;
    ReconstructOptions options;
    double grow = 0.0;
    bool noGroundClearance = false;
};

float unitScale(const std::string& unit) {
    if (unit == "m") return 1.0f;
    if (unit == "cm") return 0.01f;
    if (unit == "mm") return 0.001f;
    throw Error("unknown unit", {.parameter = "--unit", .value = unit, .validRange = "m, cm, mm"});
}

std::function<int()> setupReconstruct(CLI::App& app, GlobalOptions& global) {
    app.description(
        "Rebuild measured plants on their skeletons (.csv node table, .json, .mtg) with a "
        "species' leaves and buds");
    auto a = std::make_shared<ReconstructArgs>();
    app.add_option("skeleton", a->input, "Skeleton file: .csv node table, .json or .mtg")
        ->required();
    app.add_option("--species", a->species, "Species giving the shoot types, leaves and buds")
        ->required();
    app.add_option("-o,--output", a->outputs,
                   "Output file(s): " + outputExtensions(kSceneOutput | kPlantOutput))
        ->required();
    app.add_option("--age", a->options.age, "Age of the measured plant, days (0 to 100000)")
        ->check(CLI::Range(0.0f, 100000.0f));
    app.add_option("--unit", a->unit, "Unit of the skeleton's coordinates and radii: m, cm, mm");
    app.add_option("--spacing", a->options.spacing,
                   "Resample each axis to internodes of about this length, m (0: every point "
                   "is a node; 0 to 10)")
        ->check(CLI::Range(0.0f, 10.0f));
    app.add_option("--leaf-scale", a->options.shoot.leafScale,
                   "Leaf size on the measured nodes as a fraction of full size, (0, 1]");
    app.add_option("--attach-tolerance", a->options.shoot.attachTolerance,
                   "How far a branch's first point may be from its parent's node, m (0 to 10)");
    app.add_option("--base-type", a->options.baseShootType,
                   "Shoot type of the base stem (default: the species')");
    app.add_option("--branch-type", a->options.branchShootType,
                   "Shoot type of branches that name none (default: the parent type's most "
                   "probable child type)");
    app.add_option("--grow", a->grow, "Grow the rebuilt plants on by this many days")
        ->check(daysCheck("--grow"));
    app.add_flag("--no-ground-clearance", a->noGroundClearance, kNoGroundClearanceHelp);
    addImageSizeOption(app, global);
    addStringDigitsOption(app, global);
    addLabelOptions(app, global);
    return [a, &global]() {
        a->options.unit = unitScale(a->unit);
        checkSceneOutputs(a->outputs, global.points, true);
        CommandOutputs outputs(a->outputs);
        const Skeleton skeleton = readSkeletonFile(a->input);
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.setSeed(global.seed);
        arch.setTriangleLimit(global.maxTriangles);
        arch.setMeshDetail(global.meshDetail);
        arch.setProgressCallback(terminalProgress());
        arch.loadPlantModelFromLibrary(a->species);
        if (a->noGroundClearance) arch.setGroundClearance(false);
        const std::vector<unsigned> plants = reconstructPlants(arch, skeleton, a->options);
        if (a->grow > 0.0) arch.advanceTime(plants, a->grow);
        for (const std::string& out : a->outputs)
            writePlantFile(arch, plants, out, plantFileOptions(global));
        outputs.commit();
        std::size_t shoots = 0, leaves = 0;
        for (unsigned p : plants) {
            shoots += arch.getShootCount(p);
            leaves += arch.getPlantLeafCount(p);
        }
        std::printf("%s", fmt::format("{} plant(s) rebuilt on {} nodes: {} shoots, {} leaves, "
                                      "{} triangles.\n",
                                      plants.size(), skeleton.nodes.size(), shoots, leaves,
                                      ctx.triangleCount())
                              .c_str());
        return 0;
    };
}

}  // namespace

PLANTARCH_REGISTER_COMMAND(reconstruct, "reconstruct", 37, setupReconstruct);

}  // namespace plantarch::cli
