// Plant inputs shared by the commands that read plants (plant structure files, plant
// strings and measured skeletons), and the option and file helpers their outputs share; the outputs
// themselves are written through plantarch/PlantFiles.h.

#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "cli.h"
#include "plantarch/Error.h"
#include "plantarch/InputFiles.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/Skeleton.h"

namespace plantarch::cli {

void writeWholeFile(const std::string& path, const std::string& text) {
    writeFileAtomically(path, text);
}

void requireInputFile(const std::string& path, const std::string& what, const std::string& option) {
    // The kind, for its size limit, from what the command calls the file.
    const auto kind = [&] {
        if (what == "project file") return InputFileKind::Project;
        if (what == "plant string file") return InputFileKind::PlantStrings;
        if (what == "attraction point file") return InputFileKind::AttractionPoints;
        if (what.find("OBJ") != std::string::npos || what == "obstacle file")
            return InputFileKind::OBJ;
        return InputFileKind::PlantStructure;
    }();
    try {
        checkInputFile(path, kind, what);
    } catch (const Error& e) {
        if (option.empty()) throw;
        ErrorContext c = e.context();
        c.parameter = option;
        throw Error(e.message(), c);
    }
}

std::vector<unsigned> readPlantInput(PlantArchitecture& arch, const std::string& path,
                                     const std::string& species) {
    const std::string ext = lowerExtension(path);
    PlantStructureReadOptions o;
    o.onWarning = [](const std::string& w) {
        clearProgress();
        std::fprintf(stderr, "plantarch: warning: %s\n", w.c_str());
    };
    if (ext == ".xml") {
        if (!species.empty()) arch.loadPlantModelFromLibrary(species);  // defaults for listings
        return arch.readPlantStructureXML(path, o);
    }
    if (ext == ".mtg" || ext == ".csv" || ext == ".json") {
        if (species.empty())
            throw Error("a skeleton gives points only: give the species with --species",
                        {.file = path,
                         .parameter = "--species",
                         .validRange = "a library species or species file"});
        const Skeleton skeleton = readSkeletonFile(path);  // read before the species loads
        arch.loadPlantModelFromLibrary(species);
        return reconstructPlants(arch, skeleton);
    }
    if (ext != ".txt")
        throw Error("unknown plant file format",
                    {.file = path,
                     .value = ext,
                     .validRange = ".xml, .txt, or a skeleton: .mtg, .csv, .json"});
    if (species.empty())
        throw Error("plant strings name shoot types only: give the species with --species",
                    {.file = path,
                     .parameter = "--species",
                     .validRange = "a library species or species file"});
    requireInputFile(path, "plant string file");
    arch.loadPlantModelFromLibrary(species);
    std::istringstream in(readInputFile(path, InputFileKind::PlantStrings));
    std::vector<unsigned> ids;
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        try {
            ids.push_back(arch.generatePlantFromString(line, o));
        } catch (const Error& e) {
            throw e.withFile(path, number);
        }
    }
    if (ids.empty())
        throw Error("the file holds no plant strings",
                    {.file = path, .validRange = "one plant string per line"});
    return ids;
}

void addStringDigitsOption(CLI::App& app, GlobalOptions& global) {
    app.add_option("--digits", global.stringDigits,
                   "Significant digits of plant strings in .txt outputs (1 to 6, 0 exact; "
                   "default 4)")
        ->check(
            numberCheck("--digits", "a digit count", 0, 6, true, "1 to 6, or 0 for exact values"));
}

}  // namespace plantarch::cli
