// plantarch convert IN OUT
// Converts between plant structure files (.xml), plant strings (.txt) and geometry (.obj,
// .ply, .glb, ...): a plant file can become any of them; an OBJ file (geometry only) can
// become any geometry format, keeping the labels plantarch wrote into it.

#include <filesystem>

#include "cli.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/PlantStructureWrite.h"

namespace plantarch::cli {

namespace {

struct ConvertArgs {
    std::string input, output, species;
};

std::function<int()> setupConvert(CLI::App& app, GlobalOptions& global) {
    app.description(
        "Convert plants between .xml (plant structure), .txt (plant strings), "
        ".obj, .ply and .png");
    auto a = std::make_shared<ConvertArgs>();
    app.add_option("input", a->input, "Plant file (.xml or .txt) or geometry (.obj)")->required();
    app.add_option("output", a->output,
                   "Output file: " + outputExtensions(kSceneOutput | kPlantOutput))
        ->required();
    app.add_option("--species", a->species,
                   "Species giving the shoot types of plant strings (.txt input) and the "
                   "defaults of listing-form .xml files");
    addImageSizeOption(app, global);
    addStringDigitsOption(app, global);
    addLabelOptions(app, global);
    return [a, &global]() {
        checkSceneOutputs({a->output}, global.points, true);
        checkMaterialOutputs(global, {a->output});
        const std::string in = lowerExtension(a->input);
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.setSeed(global.seed);
        arch.setTriangleLimit(global.maxTriangles);
        arch.setMeshDetail(global.meshDetail);
        if (in == ".obj") {
            requireOutputFormat(a->output, kSceneOutput,
                                "an OBJ file holds geometry only, not the plant structure");
            CommandOutputs outputs({a->output});
            // The labels of a plantarch OBJ (its label comments) and its object IDs come
            // along into every format that holds labels.
            readOBJ(ctx, a->input, {.progress = terminalProgress()});
            writeSceneFile(ctx, a->output, plantFileOptions(global));
            if (global.objectIDs && holdsObjectIDs(a->output)) {
                writeObjectTableJSON(ctx, objectTablePath(a->output));
                info(global, "wrote " + objectTablePath(a->output));
            }
            outputs.commit();
            return 0;
        }
        CommandOutputs outputs({a->output});
        const std::vector<unsigned> plants = readPlantInput(arch, a->input, a->species);
        info(global, "read " + std::to_string(plants.size()) + " plant(s) from " + a->input);
        writePlantFile(arch, plants, a->output, plantFileOptions(global));
        outputs.commit();
        return 0;
    };
}

}  // namespace

PLANTARCH_REGISTER_COMMAND(convert, "convert", 35, setupConvert);

}  // namespace plantarch::cli
