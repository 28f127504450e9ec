// plantarch validate: reads a species file strictly, defines its shoot types and builds its
// initial structure once, and prints one line: "FILE: ok (N shoot types)". A file with errors
// gets one line on stderr per error (each bad value, unknown element or value out of range;
// reading stops only where the file cannot be read further, such as malformed XML); then each
// file it names (textures, OBJ models) that is missing or not what it should be.

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "cli.h"
#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/SpeciesBuild.h"
#include "plantarch/SpeciesIO.h"

namespace plantarch::cli {
namespace {

// Every error of the file, one line each on stderr; returns how many there were.
std::size_t reportErrors(const std::string& file) {
    namespace fs = std::filesystem;
    std::error_code ec;
    std::string path = file;
    if (!fs::exists(file, ec)) {
        const fs::path library = fs::path(speciesLibraryDirectory()) / (file + ".xml");
        if (!fs::is_regular_file(library, ec)) {
            loadSpecies(file);  // throws: unknown species, with the nearest name
            return 0;
        }
        path = library.string();
    }
    std::vector<Error> errors = checkSpeciesFile(path);
    // The files it names (textures, OBJ models), once the file itself reads.
    if (errors.empty()) errors = checkSpeciesFiles(readSpeciesFile(path));
    for (const Error& e : errors) std::fprintf(stderr, "plantarch: %s\n", e.what());
    return errors.size();
}

int run(const std::string& file, const GlobalOptions& g) {
    if (reportErrors(file) > 0) return 2;
    const SpeciesModel species = loadSpecies(file);
    // Reading checks the file itself; a trial build also checks what only a
    // PlantArchitecture knows (registered prototype functions) and the build steps' values.
    Context context;
    PlantArchitecture arch(&context);
    arch.setSeed(g.seed);
    defineSpeciesShootTypes(arch, species);
    const unsigned plant = arch.addPlantInstance(vec3(0.0f), 0.0f);
    const std::vector<unsigned> shoots = buildInitialStructure(arch, plant, species);
    info(g, species.sourceFile + ": initial structure of " + std::to_string(shoots.size()) +
                " shoots");
    std::printf("%s: ok (%zu shoot type%s)\n", file.c_str(), species.shootTypes.size(),
                species.shootTypes.size() == 1 ? "" : "s");
    return 0;
}

std::function<int()> setupValidate(CLI::App& app, GlobalOptions& global) {
    app.description(
        "Check a species file strictly (exit 0 if valid; 2 and one line per error if not)");
    auto file = std::make_shared<std::string>();
    app.add_option("FILE", *file, "Species file, or the name of a library species")->required();
    return [file, &global] { return run(*file, global); };
}

}  // namespace

PLANTARCH_REGISTER_COMMAND(validate, "validate", 80, setupValidate);

}  // namespace plantarch::cli
