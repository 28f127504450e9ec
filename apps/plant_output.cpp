// Plant outputs and inputs shared by the commands that make or read plants: plant structure
// files (.xml), plant strings (.txt) and, through writeSceneFile, the scene formats.

#include <fmt/format.h>
#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "cli.h"
#include "plantarch/Error.h"
#include "plantarch/ExportPlants.h"
#include "plantarch/HeliosPlantXML.h"
#include "plantarch/InputFiles.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/PlantStructureWrite.h"

namespace plantarch::cli {

void writeWholeFile(const std::string& path, const std::string& text) {
    writeFileAtomically(path, text);
}

namespace {

// A `<helios>` plant structure file (the reference system's layout): name ends .helios.xml.
bool isHeliosPath(const std::string& path) {
    const std::string name = std::filesystem::path(path).filename().string();
    constexpr std::string_view suffix = ".helios.xml";
    if (name.size() <= suffix.size()) return false;
    std::string tail = name.substr(name.size() - suffix.size());
    for (char& c : tail) c = char(std::tolower(static_cast<unsigned char>(c)));
    return tail == suffix;
}

}  // namespace

void writePlantOutput(const PlantArchitecture& arch, const std::vector<unsigned>& plants,
                      const std::string& path, const GlobalOptions& g) {
    const std::string ext = lowerExtension(path);
    if (ext == ".xml" && isHeliosPath(path)) {
        writeHeliosPlantStructureXML(arch, plants, path);
    } else if (ext == ".xml") {
        PlantStructureWriteOptions o;
        o.objectIDs = g.objectIDs;
        writePlantStructureXML(arch, plants, path, o);
    } else if (ext == ".csv") {
        writeQSM(arch, plants, path);
    } else if (ext == ".txt") {
        PlantStringOptions o;
        o.significantDigits = g.stringDigits;
        std::string text;
        for (unsigned id : plants) text += arch.getPlantString(id, o) + "\n";
        writeWholeFile(path, text);
    } else {
        writeSceneFile(const_cast<PlantArchitecture&>(arch).context(), path, g, exportPlants(arch));
        if (g.objectIDs && hasObjectIDs(path)) {
            writeObjectTableJSON(arch, plants, objectTablePath(path));
            info(g, "wrote " + objectTablePath(path));
        }
        return;
    }
    info(g, "wrote " + path);
}

namespace {

// One plant's objects (and its trellis) copied into `to`, with their materials and data,
// moved by `shift`.
void copyPlant(const PlantArchitecture& arch, unsigned plant, Context& to, const vec3& shift) {
    const Context& from = const_cast<PlantArchitecture&>(arch).context();
    std::vector<ObjectID> ids = arch.getAllPlantObjectIDs(plant);
    const std::vector<ObjectID> trellis = arch.getPlantTrellisObjectIDs(plant);
    ids.insert(ids.end(), trellis.begin(), trellis.end());
    const std::vector<std::string> labels = from.objectDataLabels();
    for (ObjectID id : ids) {
        if (from.isObjectHidden(id)) continue;
        Mesh mesh = from.objectMesh(id);
        for (vec3& v : mesh.positions) v += shift;
        const ObjectID copy = to.addObject(mesh, from.material(from.objectMaterial(id)));
        for (const std::string& label : labels)
            if (auto value = from.objectData(id, label)) to.setObjectData(copy, label, *value);
    }
}

std::string jsonText(const std::string& text) {
    std::string out = "\"";
    for (char c : text) {
        if (c == '"' || c == '\\') out += '\\';
        out += c;
    }
    return out + "\"";
}

}  // namespace

std::string separateFileName(const std::string& path, unsigned plant) {
    const std::filesystem::path p(path);
    char id[16];
    std::snprintf(id, sizeof id, "_%04u", plant);
    // field.helios.xml -> field_0007.helios.xml: the double suffix stays whole.
    std::string stem = p.stem().string(), ext = p.extension().string();
    if (isHeliosPath(path)) {
        ext = stem.substr(stem.size() - 7) + ext;
        stem.resize(stem.size() - 7);
    }
    return (p.parent_path() / (stem + id + ext)).string();
}

std::string separateIndexName(const std::string& path) {
    const std::filesystem::path p(path);
    return (p.parent_path() / (p.stem().string() + "_index.json")).string();
}

void writeSeparatePlantOutputs(const PlantArchitecture& arch, const std::vector<unsigned>& plants,
                               const std::vector<std::string>& paths, bool ownOrigin,
                               const GlobalOptions& g) {
    // The plants' species (several, in plant order, for a project of several blocks).
    std::string species;
    for (unsigned id : plants)
        if (species.empty() ||
            (", " + species + ",").find(", " + arch.plant(id).name + ",") == std::string::npos)
            species += (species.empty() ? "" : ", ") + arch.plant(id).name;
    if (plants.empty()) species = arch.getCurrentPlantModel();
    std::string index =
        "{\n  \"species\": " + jsonText(species) + ",\n  \"seed\": " + std::to_string(arch.seed()) +
        ",\n  \"coordinates\": " + (ownOrigin ? "\"plant\"" : "\"scene\"") + ",\n  \"plants\": [";
    // One bar over the plants; each file's own writing is too short to show.
    const ProgressCallback progress = terminalProgress();
    for (std::size_t i = 0; i < plants.size(); ++i) {
        if (progress) progress("writing files", double(i) / double(plants.size()));
        const unsigned id = plants[i];
        const vec3 base = arch.getPlantBasePosition(id);
        std::string files;
        for (const std::string& path : paths) {
            const std::string file = separateFileName(path, id);
            const std::string ext = lowerExtension(path);
            if (ext == ".xml" || ext == ".txt" || ext == ".csv") {
                writePlantOutput(arch, {id}, file, g);
            } else {
                Context one;
                copyPlant(arch, id, one, ownOrigin ? -base : vec3(0.0f));
                GltfPlant described{std::int32_t(id), arch.plant(id).name,
                                    ownOrigin ? vec3(0.0f) : base, arch.plant(id).age, arch.seed()};
                writeSceneFile(one, file, g, {described}, false);
            }
            files += (files.empty() ? "" : ", ") +
                     jsonText(std::filesystem::path(file).filename().string());
        }
        index += fmt::format(
            "{}\n    {{\"plantID\": {}, \"files\": [{}], \"position\": [{}, {}, {}], "
            "\"species\": {}, \"age\": {}, \"seed\": {}}}",
            i ? "," : "", id, files, base.x, base.y, base.z, jsonText(arch.plant(id).name),
            arch.plant(id).age, arch.seed());
    }
    if (progress) progress("writing files", 1.0);
    index += "\n  ]\n}\n";
    writeWholeFile(separateIndexName(paths.front()), index);
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
    if (ext != ".txt")
        throw Error("unknown plant file format",
                    {.file = path, .value = ext, .validRange = ".xml, .txt"});
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
