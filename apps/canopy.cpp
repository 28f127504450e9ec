// plantarch canopy SPECIES --count NxM --spacing DXxDY --age D [--germination G]
//                 [-D name=value ...] -o FILE [--stats] [--carbon/--nitrogen ... --from D]
// Builds a grid canopy of a species, in parallel, and writes it (any scene or plant format),
// whole or one file per plant (--separate).

#include <fmt/format.h>

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "cli.h"
#include "leaf_angle_option.h"
#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"

namespace plantarch::cli {

namespace {

struct CanopyArgs {
    bool noTrellis = false;
    std::string species, count = "10x10", spacing = "0.3x0.3";
    float age = -1.0f, germination = 1.0f;
    std::vector<std::string> defines;
    std::vector<std::string> outputs;
    bool stats = false;
    bool separate = false, plantOrigin = false;
    CollisionArgs collision;
    AnimationArgs animation;
    PhysiologyArgs physiology;
    std::string leafAngles;
};

std::function<int()> setupCanopy(CLI::App& app, GlobalOptions& global) {
    app.description("Build a grid canopy of a species grown to an age and write it");
    auto a = std::make_shared<CanopyArgs>();
    app.add_option("species", a->species, "Library species name or species file (.xml)")
        ->required();
    app.add_option("--count", a->count, "Plants along x and y, e.g. 10x10");
    app.add_option("--spacing", a->spacing, "Plant spacing along x and y in metres, e.g. 0.3x0.3");
    app.add_option("--age", a->age, "Plant age in days (0 to 100000)")->check(daysCheck("--age"));
    addLeafAngleOption(app, a->leafAngles);
    addAnimationOptions(app, a->animation, "of age");
    app.add_option("--germination", a->germination,
                   "Probability each position has a plant (0 to 1)")
        ->check(numberCheck("--germination", "a probability", 0.0, 1.0, false, "0 to 1"));
    app.add_option("-D", a->defines, "Build parameter override, name=value (repeatable)");
    app.add_flag("--no-trellis", a->noTrellis,
                 "Leave out the species' trellis (posts and wires drawn with trellis species)");
    app.add_option("-o,--output", a->outputs,
                   "Output file(s): " + outputExtensions(kSceneOutput | kPlantOutput) +
                       " (none with --stats)");
    addImageSizeOption(app, global);
    addStringDigitsOption(app, global);
    addLabelOptions(app, global);
    app.add_flag("--stats", a->stats, "Print one JSON object per plant with its statistics");
    app.add_flag("--separate", a->separate,
                 "One file per plant for each output (field.glb -> field_0007.glb ...) and one "
                 "index, field_index.json, of plant IDs, files, positions, species and seed");
    app.add_flag(
        "--plant-origin", a->plantOrigin,
        "With --separate: each plant moved to its own origin (default: scene coordinates)");
    addCollisionOptions(app, a->collision);
    addPhysiologyOptions(app, a->physiology, true);
    return [a, &global]() {
        const auto [nx, ny] = parsePair<int>(a->count, "--count");
        const auto [sx, sy] = parsePair<float>(a->spacing, "--spacing");
        if (a->separate && a->outputs.empty())
            throw Error("--separate writes files: give -o FILE", {.parameter = "--separate"});
        if (a->separate && !a->animation.frames.empty())
            throw Error("--separate writes still files, one per plant: not with --frames",
                        {.parameter = "--separate", .validRange = "without --frames"});
        const std::optional<GrowthFrames> frames =
            prepareGrowthOutputs(a->outputs, a->stats || !a->physiology.series.empty(), a->age,
                                 a->animation, global.points);
        checkLevelOutputs(global, a->outputs, frames.has_value());  // lod_options.cpp
        checkNodeOutputs(global, a->outputs, frames.has_value());   // node_options.cpp
        checkSkinOutputs(global, frames.has_value(), a->separate);  // skin_options.cpp
        checkMaterialOutputs(global, a->outputs);                   // material_options.cpp
        checkPhysiologyOptions(a->physiology);
        const float buildAge = physiologyBuildAge(a->physiology, a->age, frames.has_value());
        if (a->plantOrigin && !a->separate)
            throw Error("--plant-origin places the plants of separate files",
                        {.parameter = "--plant-origin", .validRange = "with --separate"});
        checkCollisionOptions(a->collision);
        // Separate files get their names once the plants are known: their folder is checked
        // through the index's name.
        CommandOutputs outputs(
            a->separate ? std::vector<std::string>{separatePlantIndexName(a->outputs.front())}
                        : a->outputs);
        if (!a->physiology.series.empty()) outputs.add(a->physiology.series);
        if (!a->physiology.weather.empty())
            outputs.requireNotAnInput(a->physiology.weather, "--weather");
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.setSeed(global.seed);
        arch.setTriangleLimit(global.maxTriangles);
        arch.setProgressCallback(terminalProgress());
        arch.setMeshDetail(global.meshDetail);
        const auto started = std::chrono::steady_clock::now();  // for -v
        loadSpeciesWithLeafAngles(arch, a->species, a->leafAngles);
        arch.setTrellisGeometry(!a->noTrellis);
        applyCollisionOptions(a->collision, arch, ctx);
        const auto plants = arch.buildPlantCanopyFromLibrary(
            vec3(0.0f), vec2(sx, sy), glm::ivec2(nx, ny), frames ? 0.0f : buildAge, a->germination,
            parseDefines(a->defines));
        if (physiologyOn(a->physiology))
            growWithPhysiology(arch, plants, a->physiology, a->age - buildAge);
        info(global, fmt::format("plantarch: species loaded and {} in {:.2f} ms",
                                 frames ? "planted" : "grown", millisecondsSince(started)));
        if (frames) {
            arch.setProgressCallback({});  // one bar over the frames instead of one per frame
            writeGrowthAnimation(arch, plants, *frames, a->outputs,
                                 {a->animation.rate, terminalProgress(), global.appearance});
        } else if (a->separate)
            writeSeparatePlantFiles(arch, plants, a->outputs, a->plantOrigin,
                                    plantFileOptions(global));
        else
            for (const std::string& out : a->outputs)
                writePlantFile(arch, plants, out, plantFileOptions(global));
        // Statistics before the files go in place: commit() checks that they were written.
        if (a->stats)
            for (unsigned p : plants)
                std::printf("%s\n", plantStatsJSON(arch, ctx, p, global.seed).c_str());
        outputs.commit();
        if (a->stats) return 0;
        std::size_t leaves = 0;
        double area = 0.0;
        for (unsigned p : plants) {
            leaves += arch.getPlantLeafCount(p);
            area += arch.getPlantLeafArea(p);
        }
        std::printf("%s", fmt::format("{} canopy: {} plants of {}x{} positions, {} days (seed {}): "
                                      "{} leaves, {:.3f} m^2 leaf area, {} triangles.\n",
                                      arch.getCurrentPlantModel(), plants.size(), nx, ny,
                                      frames ? float(frames->end) : a->age, global.seed, leaves,
                                      area, ctx.triangleCount())
                              .c_str());
        return 0;
    };
}

}  // namespace

PLANTARCH_REGISTER_COMMAND(canopy, "canopy", 30, setupCanopy);

}  // namespace plantarch::cli
