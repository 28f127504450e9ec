// plantarch grow IN.xml --days N -o OUT [-o OUT ...] [--no-ground-clearance]
// plantarch grow IN.xml --frames START:END[:STEP] -o growth.glb|.usda
// Continues the growth of saved plants: reads a plant structure file, grows every plant in
// it by N days and writes the result (.xml to save it again, or .txt, .obj, .ply, .glb, .gltf,
// .png).

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "bend_options.h"
#include "cli.h"
#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"

namespace plantarch::cli {

namespace {

struct GrowArgs {
    std::string input, species;
    double days = -1.0;
    std::vector<std::string> outputs;
    AnimationArgs animation;
    bool noGroundClearance = false;
    PhysiologyArgs physiology;
    BendArgs bend;
};

std::function<int()> setupGrow(CLI::App& app, GlobalOptions& global) {
    app.description("Grow the plants of a plant structure file (.xml) on by a number of days");
    auto a = std::make_shared<GrowArgs>();
    app.add_option("input", a->input, "Plant structure file (.xml) or plant strings (.txt)")
        ->required();
    app.add_option("--days", a->days, "Days to grow (0 to 100000)")->check(daysCheck("--days"));
    addAnimationOptions(app, a->animation, "of growth from the file's state");
    app.add_option("-o,--output", a->outputs,
                   "Output file(s): " + outputExtensions(kSceneOutput | kPlantOutput))
        ->required();
    app.add_option("--species", a->species,
                   "Species giving the shoot types of plant strings (.txt input)");
    app.add_flag("--no-ground-clearance", a->noGroundClearance, kNoGroundClearanceHelp);
    addImageSizeOption(app, global);
    addStringDigitsOption(app, global);
    addLabelOptions(app, global);
    addPhysiologyOptions(app, a->physiology, false);
    addBendOptions(app, a->bend);
    return [a, &global]() {
        const std::optional<GrowthFrames> frames = parseFrames(a->animation);
        if (frames && a->days >= 0.0)
            throw Error("--days and --frames both given: --frames gives the days of the frames");
        if (!frames && a->days < 0.0)
            throw Error("--days is required (or --frames for a growth animation)");
        checkLevelOutputs(global, a->outputs, frames.has_value());  // lod_options.cpp
        checkNodeOutputs(global, a->outputs, frames.has_value());   // node_options.cpp
        checkSkinOutputs(global, frames.has_value());               // skin_options.cpp
        checkMaterialOutputs(global, a->outputs);                   // material_options.cpp
        checkPhysiologyOptions(a->physiology);
        checkBendOptions(a->bend);
        if (frames && (!a->bend.pull.empty() || !a->bend.displace.empty()))
            throw Error("--pull and --displace bend the plants after --days, not --frames");
        if (frames && physiologyOn(a->physiology))
            throw Error("--carbon/--nitrogen grow with --days, not --frames");
        if (frames)
            checkAnimationOutputs(a->outputs);
        else
            checkSceneOutputs(a->outputs, global.points, true);
        CommandOutputs outputs(a->outputs);
        if (!a->physiology.series.empty()) outputs.add(a->physiology.series);
        if (!a->physiology.weather.empty())
            outputs.requireNotAnInput(a->physiology.weather, "--weather");
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.setSeed(global.seed);
        arch.setTriangleLimit(global.maxTriangles);
        arch.setMeshDetail(global.meshDetail);
        arch.setProgressCallback(terminalProgress());
        const auto started = std::chrono::steady_clock::now();  // for -v
        const std::vector<unsigned> plants = readPlantInput(arch, a->input, a->species);
        info(global,
             fmt::format("plantarch: {} read in {:.2f} ms", a->input, millisecondsSince(started)));
        if (a->noGroundClearance) arch.setGroundClearance(false);
        enableBending(arch, plants, a->bend);
        if (frames) {
            arch.setProgressCallback({});  // one bar over the frames instead of one per frame
            writeGrowthAnimation(arch, plants, *frames, a->outputs,
                                 {a->animation.rate, terminalProgress(), global.appearance});
        } else {
            if (physiologyOn(a->physiology))
                growWithPhysiology(arch, plants, a->physiology, a->days);
            else
                arch.advanceTime(plants, a->days);
            applyBending(arch, plants, a->bend, stdout);
            for (const std::string& out : a->outputs)
                writePlantFile(arch, plants, out, plantFileOptions(global));
        }
        outputs.commit();
        std::size_t leaves = 0;
        for (unsigned p : plants) leaves += arch.getPlantLeafCount(p);
        std::printf("%s", fmt::format("{} plant(s) grown {} days: {} leaves, {} triangles.\n",
                                      plants.size(), frames ? frames->end : a->days, leaves,
                                      ctx.triangleCount())
                              .c_str());
        return 0;
    };
}

}  // namespace

PLANTARCH_REGISTER_COMMAND(grow, "grow", 36, setupGrow);

}  // namespace plantarch::cli
