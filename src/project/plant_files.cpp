// Plants and scenes written to the files a user names (plantarch/PlantFiles.h): the format
// from the extension, for the command line and the project builder alike.

#include <fmt/format.h>

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <string>

#include "plantarch/Error.h"
#include "plantarch/ExportPlants.h"
#include "plantarch/HeliosPlantXML.h"
#include "plantarch/OutputFiles.h"
#include "plantarch/OutputFormats.h"
#include "plantarch/PlantFiles.h"
#include "plantarch/PlantStructureWrite.h"
#include "plantarch/Skeleton.h"

namespace plantarch {

namespace {

void written(const PlantFileOptions& options, const std::string& path) {
    if (options.onWritten) options.onWritten(path);
}

}  // namespace

bool holdsObjectIDs(const std::string& path) {
    const std::string ext = lowerExtension(path);
    return ext == ".obj" || ext == ".ply" || ext == ".glb" || ext == ".gltf" || ext == ".usda" ||
           ext == ".npz";
}

std::string objectTablePath(const std::string& path) {
    const std::filesystem::path p(path);
    return (p.parent_path() / (p.stem().string() + ".objects.json")).string();
}

void writeSceneFile(const Context& ctx, const std::string& path, const PlantFileOptions& g,
                    const std::vector<GltfPlant>& plants,
                    const std::vector<GltfSkeleton>& skeletons) {
    const std::string ext = lowerExtension(path);
    const ProgressCallback& progress = g.progress;
    if ((!g.levels.empty() || g.meshoptCompression) && ext != ".glb" && ext != ".gltf" &&
        ext != ".png")
        throw Error("levels of detail and meshopt compression are written in glTF only",
                    {.file = path,
                     .parameter = g.levels.empty() ? "meshopt" : "lod",
                     .validRange = ".glb, .gltf"});
    if (g.nodes != NodeLevel::Kind && ext != ".glb" && ext != ".gltf" && ext != ".usda" &&
        ext != ".usdz" && ext != ".png")
        throw Error("node levels are written in glTF and USD only",
                    {.file = path,
                     .parameter = "nodes",
                     .value = nodeLevelName(g.nodes),
                     .validRange = ".glb, .gltf, .usda, .usdz"});
    auto points = [&] {
        return samplePoints(ctx, {.points = g.points, .seed = g.seed, .progress = progress});
    };
    if (ext == ".obj") {
        writeOBJ(ctx, path, {.appearance = g.appearance, .progress = progress});
    } else if (ext == ".ply" && g.points > 0) {
        writePointCloudPLY(points(), path, progress);
    } else if (ext == ".ply") {
        writePLY(ctx, path, {.format = g.plyFormat, .color = g.plyColor, .progress = progress});
    } else if (ext == ".npz" && g.points > 0) {
        writePointCloudNPZ(points(), path, progress);
    } else if (ext == ".glb" || ext == ".gltf") {
        GltfOptions o;
        o.plants = plants;
        o.skeletons = skeletons;
        o.windDegrees = g.wind;
        o.progress = progress;
        o.levels = g.levels;
        o.meshoptCompression = g.meshoptCompression;
        o.appearance = g.appearance;
        o.nodes = g.nodes;
        o.instancing = g.instancing;
        writeGLTF(ctx, path, o);
    } else if (ext == ".usda" || ext == ".usdz") {
        UsdOptions o;
        o.plants = plants;
        o.skeletons = skeletons;
        o.progress = progress;
        o.appearance = g.appearance;
        o.nodes = g.nodes;
        o.instancing = g.instancing;
        writeUSDA(ctx, path, o);
    } else if (ext == ".png") {
        RenderOptions o;
        o.width = g.imageWidth;
        o.height = g.imageHeight;
        o.progress = progress;
        o.seed = g.seed;
        o.camera = g.camera;
        o.mode = g.mode;
        o.scene.appearance = g.appearance;
        const RenderScene scene(ctx, o.scene);
        if (!o.camera.autoFrame && !g.cameraTarget) o.camera.target = scene.bounds().center();
        writePNG(scene.render(o), path);
        if (g.cameraJson) {
            const std::filesystem::path p(path);
            const std::string json =
                (p.parent_path() / (p.stem().string() + ".camera.json")).string();
            writeFileAtomically(json, cameraJSON(scene.camera(o), o.width, o.height));
            written(g, json);
        }
    } else {
        requireOutputFormat(path, kSceneOutput, "unknown output format");
        throw Error("an .npz output is a point cloud: give --points N",
                    {.file = path, .parameter = "--points", .validRange = "1 to 2147483648"});
    }
    written(g, path);
}

namespace {

// A skeleton node table: name ends .skeleton.csv.
bool isSkeletonPath(const std::string& path) {
    const std::string name = std::filesystem::path(path).filename().string();
    constexpr std::string_view suffix = ".skeleton.csv";
    if (name.size() <= suffix.size()) return false;
    std::string tail = name.substr(name.size() - suffix.size());
    for (char& c : tail) c = char(std::tolower(static_cast<unsigned char>(c)));
    return tail == suffix;
}

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

void writePlantFile(const PlantArchitecture& arch, const std::vector<unsigned>& plants,
                    const std::string& path, const PlantFileOptions& g) {
    const std::string ext = lowerExtension(path);
    if (ext == ".xml" && isHeliosPath(path)) {
        writeHeliosPlantStructureXML(arch, plants, path);
    } else if (ext == ".xml") {
        PlantStructureWriteOptions o;
        o.objectIDs = g.objectIDs;
        writePlantStructureXML(arch, plants, path, o);
    } else if (ext == ".mtg") {
        writeFileAtomically(path, plantsMTG(arch, plants));
    } else if (ext == ".csv" && isSkeletonPath(path)) {
        writeFileAtomically(path, skeletonCSV(plantSkeleton(arch, plants)));
    } else if (ext == ".csv") {
        writeQSM(arch, plants, path);
    } else if (ext == ".txt") {
        PlantStringOptions o;
        o.significantDigits = g.stringDigits;
        std::string text;
        for (unsigned id : plants) text += arch.getPlantString(id, o) + "\n";
        writeFileAtomically(path, text);
    } else {
        const bool skinned = g.skin && (ext == ".glb" || ext == ".gltf" || ext == ".usda");
        writeSceneFile(const_cast<PlantArchitecture&>(arch).context(), path, g, exportPlants(arch),
                       skinned ? exportSkeletons(arch) : std::vector<GltfSkeleton>{});
        if (g.objectIDs && holdsObjectIDs(path)) {
            writeObjectTableJSON(arch, plants, objectTablePath(path));
            written(g, objectTablePath(path));
        }
        return;
    }
    written(g, path);
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

std::string separatePlantFileName(const std::string& path, unsigned plant) {
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

std::string separatePlantIndexName(const std::string& path) {
    const std::filesystem::path p(path);
    return (p.parent_path() / (p.stem().string() + "_index.json")).string();
}

void writeSeparatePlantFiles(const PlantArchitecture& arch, const std::vector<unsigned>& plants,
                             const std::vector<std::string>& paths, bool ownOrigin,
                             const PlantFileOptions& g) {
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
    const ProgressCallback progress = g.progress;
    PlantFileOptions quiet = g;  // each file's own writing is too short to show
    quiet.progress = nullptr;
    for (std::size_t i = 0; i < plants.size(); ++i) {
        if (progress) progress("writing files", double(i) / double(plants.size()));
        const unsigned id = plants[i];
        const vec3 base = arch.getPlantBasePosition(id);
        std::string files;
        for (const std::string& path : paths) {
            const std::string file = separatePlantFileName(path, id);
            const std::string ext = lowerExtension(path);
            if (ext == ".xml" || ext == ".txt" || ext == ".csv" || ext == ".mtg") {
                writePlantFile(arch, {id}, file, quiet);
            } else {
                Context one;
                copyPlant(arch, id, one, ownOrigin ? -base : vec3(0.0f));
                GltfPlant described{std::int32_t(id), arch.plant(id).name,
                                    ownOrigin ? vec3(0.0f) : base, arch.plant(id).age, arch.seed()};
                writeSceneFile(one, file, quiet, {described});
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
    writeFileAtomically(separatePlantIndexName(paths.front()), index);
    written(g, separatePlantIndexName(paths.front()));
}

}  // namespace plantarch
