// One tile of a field: its plants (and, with soft avoidance, its halo) built from the project
// with the IDs and streams of the whole build, the halo and the scene's ground and obstacles
// removed, then its rows (NAME.csv) and its labelled geometry (NAME.glb) written.

#include <filesystem>

#include "core/atomic_file.h"
#include "core/value_text.h"
#include "dataset/field_internal.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/ExportPlants.h"
#include "plantarch/PlantArchitecture.h"

namespace plantarch {

namespace field {

std::string csvText(const std::string& s) {
    if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

std::string rowText(const FieldPlantRow& r) {
    const auto f = [](float v) { return text::formatFloat(v); };
    std::string line = std::to_string(r.id) + "," + csvText(r.block) + "," + csvText(r.species) +
                       "," + r.tile + "," + f(r.base.x) + "," + f(r.base.y) + "," + f(r.base.z) +
                       "," + f(r.age) + "," + std::to_string(r.seed) + "," +
                       std::to_string(r.stream) + "," + std::to_string(r.triangles) + "," +
                       f(r.height) + "," + f(float(r.leafArea));
    const AABB b = r.bounds.empty() ? AABB{r.base, r.base} : r.bounds;
    for (const vec3& v : {b.min, b.max}) line += "," + f(v.x) + "," + f(v.y) + "," + f(v.z);
    return line;
}

void requireFolder(const std::string& outDir) {
    if (outDir.empty())
        throw Error("no output folder", {.parameter = "out", .validRange = "a folder's path"});
    std::error_code ec;
    const auto status = std::filesystem::status(outDir, ec);
    if (std::filesystem::exists(status) && !std::filesystem::is_directory(status))
        throw Error(
            "not a folder",
            {.file = outDir, .parameter = "out", .validRange = "a folder (made if missing)"});
}

void makeFolder(const std::string& outDir) {
    requireFolder(outDir);
    std::error_code ec;
    std::filesystem::create_directories(outDir, ec);
    if (ec)
        throw Error(
            "cannot make the folder: " + ec.message(),
            {.file = outDir, .parameter = "out", .validRange = "a folder (made if missing)"});
}

}  // namespace field

std::string fieldPlantsHeader() {
    return "plant,block,species,tile,x,y,z,age,seed,stream,triangles,height,leaf_area,"
           "min_x,min_y,min_z,max_x,max_y,max_z";
}

std::vector<FieldPlantRow> buildFieldTile(const Project& project, const FieldOptions& options,
                                          std::size_t tileIndex, const std::string& outDir) {
    const FieldPlan plan = fieldTiles(project, options);
    if (tileIndex >= plan.tiles.size())
        throw Error("no such tile",
                    {.parameter = "tile",
                     .value = std::to_string(tileIndex),
                     .validRange = "0 to " + std::to_string(plan.tiles.size() - 1)});
    field::requireFolder(outDir);
    const FieldTile& tile = plan.tiles[tileIndex];
    // Each block's plants to build: the tile's and its halo, in block order.
    std::vector<std::vector<unsigned>> only(project.blocks.size());
    std::vector<FieldPlant> all = tile.plants;
    all.insert(all.end(), tile.halo.begin(), tile.halo.end());
    std::sort(all.begin(), all.end(),
              [](const FieldPlant& a, const FieldPlant& b) { return a.id < b.id; });
    for (const FieldPlant& p : all) only[p.block].push_back(p.index);

    Context ctx;
    PlantArchitecture arch(&ctx);
    const BuiltProject built = buildProject(
        project, arch,
        {.progress = options.progress, .maxTriangles = options.maxTriangles, .only = only});
    for (const FieldPlant& p : tile.halo) arch.deletePlantInstance(p.id);
    ctx.deleteObjects(built.ground);
    ctx.deleteObjects(built.obstacles);

    std::vector<FieldPlantRow> rows;
    for (const FieldPlant& p : tile.plants) {
        const ProjectBlock& b = project.blocks[p.block];
        FieldPlantRow r;
        r.id = p.id;
        r.block = b.name;
        r.species = arch.getPlantName(p.id);
        r.tile = tile.name;
        r.base = arch.getPlantBasePosition(p.id);
        r.age = arch.getPlantAge(p.id);
        r.seed = b.seed.value_or(project.seed);
        r.stream = arch.plantStream(p.id);
        r.height = arch.getPlantHeight(p.id);
        r.leafArea = arch.getPlantLeafArea(p.id);
        std::vector<ObjectID> objects = arch.getAllPlantObjectIDs(p.id);
        const std::vector<ObjectID> trellis = arch.getPlantTrellisObjectIDs(p.id);
        objects.insert(objects.end(), trellis.begin(), trellis.end());
        for (ObjectID o : objects) {
            r.triangles += ctx.object(o).triangleCount();
            const AABB box = ctx.objectBoundingBox(o);
            if (!box.empty()) {
                r.bounds.add(box.min);
                r.bounds.add(box.max);
            }
        }
        rows.push_back(std::move(r));
    }
    field::makeFolder(outDir);
    const std::filesystem::path dir(outDir);
    {
        io::AtomicFile csv((dir / (tile.name + ".csv")).string());
        csv.write(fieldPlantsHeader() + "\n");
        for (const FieldPlantRow& r : rows) csv.write(field::rowText(r) + "\n");
        csv.commit();
    }
    GltfOptions gltf;
    gltf.plants = exportPlants(arch);
    writeGLTF(ctx, (dir / (tile.name + ".glb")).string(), gltf);
    return rows;
}

}  // namespace plantarch
