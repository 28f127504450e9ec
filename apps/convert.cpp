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
    app.add_option("output", a->output, "Output file: " + plantFileExtensions())->required();
    app.add_option("--species", a->species,
                   "Species giving the shoot types of plant strings (.txt input) and the "
                   "defaults of listing-form .xml files");
    addImageSizeOption(app, global);
    addStringDigitsOption(app, global);
    addLabelOptions(app, global);
    return [a, &global]() {
        preparePlantOutputs({a->output}, global.points);
        std::string in = std::filesystem::path(a->input).extension().string();
        for (char& c : in) c = char(std::tolower(static_cast<unsigned char>(c)));
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.setSeed(global.seed);
        arch.setMeshDetail(global.meshDetail);
        if (in == ".obj") {
            std::string out = std::filesystem::path(a->output).extension().string();
            for (char& c : out) c = char(std::tolower(static_cast<unsigned char>(c)));
            if (out == ".xml" || out == ".txt")
                throw Error("an OBJ file holds geometry only, not the plant structure",
                            {.file = a->output, .value = out, .validRange = sceneFileExtensions()});
            // The labels of a plantarch OBJ (its label comments) and its object IDs come
            // along into every format that holds labels.
            readOBJ(ctx, a->input, {.progress = terminalProgress()});
            writeSceneFile(ctx, a->output, global);
            if (global.objectIDs && hasObjectIDs(a->output)) {
                writeObjectTableJSON(ctx, objectTablePath(a->output));
                info(global, "wrote " + objectTablePath(a->output));
            }
            return 0;
        }
        const std::vector<unsigned> plants = readPlantInput(arch, a->input, a->species);
        info(global, "read " + std::to_string(plants.size()) + " plant(s) from " + a->input);
        writePlantOutput(arch, plants, a->output, global);
        return 0;
    };
}

}  // namespace

PLANTARCH_REGISTER_COMMAND(convert, "convert", 35, setupConvert);

}  // namespace plantarch::cli
