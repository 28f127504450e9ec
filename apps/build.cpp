// plantarch build SPECIES --age D [-D name=value ...] -o FILE [-o FILE ...] [--stats]
// Builds one plant of a library species (or a species file) grown to an age, writes it in
// every format asked for, and prints a one-paragraph summary (or JSON with --stats).

#include <cstdio>
#include <filesystem>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "cli.h"
#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"

namespace plantarch::cli {

namespace {

struct BuildArgs {
    std::string species;
    float age = -1.0f;
    std::vector<std::string> defines;
    std::vector<std::string> outputs;
    bool stats = false;
    CollisionArgs collision;
};

std::map<std::string, float> parseDefines(const std::vector<std::string>& defines) {
    std::map<std::string, float> out;
    for (const std::string& d : defines) {
        const auto eq = d.find('=');
        if (eq == std::string::npos || eq == 0)
            throw Error("a build parameter is written name=value",
                        {.parameter = "-D", .value = d, .validRange = "name=value"});
        const std::string name = d.substr(0, eq), text = d.substr(eq + 1);
        std::size_t used = 0;
        float value = 0.0f;
        try {
            value = std::stof(text, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used == 0 || used != text.size() || !std::isfinite(value))
            throw Error("build parameter value is not a number",
                        {.parameter = name, .value = text, .validRange = "a finite number"});
        out[name] = value;
    }
    return out;
}

// Counts one plant's organs the way --stats reports them.
std::string statsJSON(const PlantArchitecture& arch, const Context& ctx, unsigned plant,
                      std::uint64_t seed) {
    const PlantInstance& p = arch.plant(plant);
    std::size_t flowers = 0, fruit = 0;
    for (const Shoot& s : p.shoots) {
        if (s.removed) continue;
        auto count = [&](const FloralBud& fb) {
            if (fb.stage == FloralStage::FlowerClosed || fb.stage == FloralStage::FlowerOpen)
                flowers += fb.flowers.size();
            if (fb.stage == FloralStage::Fruit) fruit += fb.flowers.size();
        };
        for (const Phytomer& ph : s.phytomers)
            for (const Petiole& pt : ph.petioles)
                for (const FloralBud& fb : pt.floralBuds) count(fb);
        for (const FloralBud& fb : s.terminalFloralBuds) count(fb);
    }
    std::size_t triangles = 0;
    for (ObjectID id : arch.getAllPlantObjectIDs(plant)) triangles += ctx.objectPrimitives(id).count;
    return fmt::format(
        "{{\"species\": \"{}\", \"plant\": {}, \"age\": {}, \"seed\": {}, \"height\": {:.4f}, "
        "\"leaves\": {}, \"leaf_area\": {:.5f}, \"shoots\": {}, \"flowers\": {}, \"fruit\": {}, "
        "\"triangles\": {}}}",
        p.name, plant, p.age, seed, arch.getPlantHeight(plant), arch.getPlantLeafCount(plant),
        arch.getPlantLeafArea(plant), arch.getShootCount(plant), flowers, fruit, triangles);
}

std::function<int()> setupBuild(CLI::App& app, GlobalOptions& global) {
    app.description("Build one plant of a species grown to an age and write it (OBJ, PLY, PNG)");
    auto a = std::make_shared<BuildArgs>();
    app.add_option("species", a->species, "Library species name or species file (.xml)")
        ->required();
    app.add_option("--age", a->age, "Plant age in days (0 to 100000)")
        ->required()
        ->check([](const std::string& text) -> std::string {
            try {
                const double v = std::stod(text);
                if (v >= 0.0 && v <= 100000.0) return "";
            } catch (const std::exception&) {
            }
            return "age = " + text + ": not a number of days (valid: 0 to 100000)";
        });
    app.add_option("-D", a->defines, "Build parameter override, name=value (repeatable)");
    app.add_option("-o,--output", a->outputs, "Output file(s): .obj, .ply or .png")->required();
    addImageSizeOption(app, global);
    app.add_flag("--stats", a->stats, "Print one JSON object with the plant's statistics");
    addCollisionOptions(app, a->collision);
    return [a, &global]() {
        prepareSceneOutputs(a->outputs);
        checkCollisionOptions(a->collision);
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.setSeed(global.seed);
        arch.setProgressCallback(terminalProgress());
        arch.loadPlantModelFromLibrary(a->species);
        applyCollisionOptions(a->collision, arch, ctx);
        const unsigned plant =
            arch.buildPlantInstanceFromLibrary(vec3(0.0f), a->age, parseDefines(a->defines));
        for (const std::string& out : a->outputs) writeSceneFile(ctx, out, global);
        if (a->stats) {
            std::printf("%s\n", statsJSON(arch, ctx, plant, global.seed).c_str());
        } else {
            std::string outs;
            for (const std::string& o : a->outputs) outs += (outs.empty() ? "" : ", ") + o;
            std::printf("%s", fmt::format(
                "{} at {} days (seed {}): {} shoots, {} leaves (leaflets counted), {:.4f} m^2 "
                "one-sided leaf area, {:.3f} m tall, {} triangles in {} objects; written to {}.\n",
                arch.getCurrentPlantModel(), a->age, global.seed, arch.getShootCount(plant),
                arch.getPlantLeafCount(plant), arch.getPlantLeafArea(plant),
                arch.getPlantHeight(plant), ctx.triangleCount(), ctx.objectCount(), outs).c_str());
        }
        return 0;
    };
}

}  // namespace

PLANTARCH_REGISTER_COMMAND(build, "build", 20, setupBuild);

}  // namespace plantarch::cli
