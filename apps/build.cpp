// plantarch build SPECIES --age D [-D name=value ...] -o FILE [-o FILE ...] [--stats]
// plantarch build SPECIES --frames START:END[:STEP] -o growth.glb|.usda
// Builds one plant of a library species (or a species file) grown to an age, writes it in
// every format asked for, and prints a one-paragraph summary (or JSON with --stats); with
// --frames, grows it from germination and writes the growth as an animation.

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "bend_options.h"
#include "cli.h"
#include "leaf_angle_option.h"
#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"

namespace plantarch::cli {

namespace {

struct BuildArgs {
    bool noTrellis = false;
    std::string species;
    float age = -1.0f;
    std::vector<std::string> defines;
    std::vector<std::string> outputs;
    bool stats = false;
    CollisionArgs collision;
    AnimationArgs animation;
    PhysiologyArgs physiology;
    BendArgs bend;
    std::string leafAngles;
};

std::function<int()> setupBuild(CLI::App& app, GlobalOptions& global) {
    app.description(
        "Build one plant of a species grown to an age and write it (OBJ, PLY, PNG, plant XML or "
        "string)");
    auto a = std::make_shared<BuildArgs>();
    addPlantOptions(app, a->species, a->age, a->defines, a->noTrellis);
    addLeafAngleOption(app, a->leafAngles);
    addAnimationOptions(app, a->animation, "of age");
    app.add_option("-o,--output", a->outputs,
                   "Output file(s): " + outputExtensions(kSceneOutput | kPlantOutput) +
                       " (none with --stats)");
    addImageSizeOption(app, global);
    addStringDigitsOption(app, global);
    addLabelOptions(app, global);
    app.add_flag("--stats", a->stats, "Print one JSON object with the plant's statistics");
    addCollisionOptions(app, a->collision);
    addPhysiologyOptions(app, a->physiology, true);
    addBendOptions(app, a->bend);
    return [a, &global]() {
        const std::optional<GrowthFrames> frames =
            prepareGrowthOutputs(a->outputs, a->stats || !a->physiology.series.empty(), a->age,
                                 a->animation, global.points);
        checkLevelOutputs(global, a->outputs, frames.has_value());  // lod_options.cpp
        checkNodeOutputs(global, a->outputs, frames.has_value());   // node_options.cpp
        checkSkinOutputs(global, frames.has_value());               // skin_options.cpp
        checkMaterialOutputs(global, a->outputs);                   // material_options.cpp
        checkCollisionOptions(a->collision);
        checkPhysiologyOptions(a->physiology);
        checkBendOptions(a->bend);
        if (frames && (!a->bend.pull.empty() || !a->bend.displace.empty()))
            throw Error("--pull and --displace bend the plant at --age, not --frames");
        const bool physiology = physiologyOn(a->physiology);
        const float buildAge = physiologyBuildAge(a->physiology, a->age, frames.has_value());
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
        loadSpeciesWithLeafAngles(arch, a->species, a->leafAngles);
        arch.setTrellisGeometry(!a->noTrellis);
        applyCollisionOptions(a->collision, arch, ctx);
        const unsigned plant = arch.buildPlantInstanceFromLibrary(
            vec3(0.0f), frames ? 0.0f : buildAge, parseDefines(a->defines));
        enableBending(arch, {plant}, a->bend);
        if (physiology) growWithPhysiology(arch, {plant}, a->physiology, a->age - buildAge);
        if (!frames) applyBending(arch, {plant}, a->bend, a->stats ? stderr : stdout);
        info(global, fmt::format("plantarch: species loaded and {} in {:.2f} ms",
                                 frames ? "planted" : "grown", millisecondsSince(started)));
        if (frames) {
            arch.setProgressCallback({});  // one bar over the frames instead of one per frame
            writeGrowthAnimation(arch, {plant}, *frames, a->outputs,
                                 {a->animation.rate, terminalProgress(), global.appearance});
        } else {
            for (const std::string& out : a->outputs)
                writePlantFile(arch, {plant}, out, plantFileOptions(global));
        }
        // Statistics are printed before the files are put in place, so that a failed write of
        // them (checked by commit()) leaves no file either.
        if (a->stats) std::printf("%s\n", plantStatsJSON(arch, ctx, plant, global.seed).c_str());
        outputs.commit();
        if (!a->stats) {
            std::string outs;
            for (const std::string& o : a->outputs) outs += (outs.empty() ? "" : ", ") + o;
            if (!a->physiology.series.empty())
                outs += (outs.empty() ? "" : ", ") + a->physiology.series;
            std::printf(
                "%s",
                fmt::format(
                    "{} at {} days (seed {}): {} shoots, {} leaves (leaflets counted), {:.4f} m^2 "
                    "one-sided leaf area, {:.3f} m tall, {} triangles in {} objects; {}written "
                    "to {}.\n",
                    arch.getCurrentPlantModel(), arch.plant(plant).age, global.seed,
                    arch.getShootCount(plant), arch.getPlantLeafCount(plant),
                    arch.getPlantLeafArea(plant), arch.getPlantHeight(plant), ctx.triangleCount(),
                    ctx.objectCount(),
                    frames ? fmt::format("its growth in {} frames from {} days ",
                                         growthFrameDays(*frames).size(), frames->start)
                           : std::string(),
                    outs)
                    .c_str());
        }
        return 0;
    };
}

}  // namespace

PLANTARCH_REGISTER_COMMAND(build, "build", 20, setupBuild);

}  // namespace plantarch::cli
