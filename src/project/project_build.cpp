// Building a project: ground, obstacles, collision avoidance and attraction points, then each
// block of plants in order, into one PlantArchitecture and its Context.

#include <algorithm>
#include <filesystem>

#include "core/input_file.h"
#include "core/value_text.h"
#include "plantarch/Bending.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/Project.h"
#include "plantarch/Skeleton.h"
#include "plantarch/SpeciesIO.h"
#include "project/json_scan.h"
#include "project/project_fields.h"

namespace plantarch {

namespace {

std::string fileOf(const Project& p) {
    return p.file.empty() ? "project" : p.file;
}

// An error of the library raised while handling `field`: it names the project file and the
// field (the library's own parameter in brackets), unless it already names a file of its own
// (a species file's error points into that file). A triangle budget keeps its type.
[[noreturn]] void rethrowAt(const Project& p, const std::string& field) {
    try {
        throw;
    } catch (const TriangleBudgetError&) {
        throw;
    } catch (const Error& e) {
        if (!e.file().empty()) throw;
        // The library's own name for the value, unless the field says it already.
        const bool named = e.parameter().empty() || field.ends_with("/" + e.parameter());
        throw Error(e.message(), {.file = fileOf(p),
                                  .parameter = field + (named ? "" : " (" + e.parameter() + ")"),
                                  .value = e.value(),
                                  .validRange = e.validRange()});
    }
}

bool isSpeciesPath(const std::string& species) {
    return species.find('/') != std::string::npos ||
           (species.size() > 4 && species.compare(species.size() - 4, 4, ".xml") == 0);
}

// A block's species file exists and is a regular file: else an error naming the project file,
// the field and the path looked for (the species reader's own error would name only the
// species file, which the user never typed as such).
void requireSpeciesFile(const Project& p, std::size_t i) {
    const ProjectBlock& b = p.blocks[i];
    if (!isSpeciesPath(b.species)) return;
    const std::string full = projectPath(p, b.species);
    std::error_code ec;
    const auto status = std::filesystem::status(full, ec);
    const std::string field = "blocks/" + std::to_string(i) + "/species";
    const std::string valid = "a library species name or a species file (.xml)";
    if (!std::filesystem::exists(status))
        throw Error(
            "no such species file" + (full == b.species ? "" : " (" + full + ")"),
            {.file = fileOf(p), .parameter = field, .value = b.species, .validRange = valid});
    if (!std::filesystem::is_regular_file(status))
        throw Error(
            std::string(std::filesystem::is_directory(status) ? "a directory"
                                                              : "not a regular file") +
                ", not a species file" + (full == b.species ? "" : " (" + full + ")"),
            {.file = fileOf(p), .parameter = field, .value = b.species, .validRange = valid});
}

// The species of every block, loaded and its build parameters checked.
std::vector<SpeciesModel> loadBlockSpecies(const Project& p) {
    std::vector<SpeciesModel> models;
    std::map<std::string, SpeciesModel> loaded;  // by species reference: each read once
    for (std::size_t i = 0; i < p.blocks.size(); ++i) {
        const ProjectBlock& b = p.blocks[i];
        const std::string at = "blocks/" + std::to_string(i);
        const std::string species = projectSpecies(p, b);
        requireSpeciesFile(p, i);
        if (const auto it = loaded.find(species); it != loaded.end()) {
            models.push_back(it->second);
        } else {
            try {
                models.push_back(loadSpecies(species));
            } catch (const Error&) {
                rethrowAt(p, at + "/species");
            }
            loaded.emplace(species, models.back());
        }
        for (const auto& [name, value] : b.speciesParameters) {
            try {
                models.back() = editSpecies(models.back(), {{name, value}});
            } catch (const Error& e) {
                throw Error(e.message(), {.file = fileOf(p),
                                          .parameter = at + "/species_parameters/" +
                                                       project::printable(name, 80),
                                          .value = value,
                                          .validRange = e.validRange()});
            }
        }
        for (const auto& [name, value] : b.parameters) {
            try {
                resolveBuildParameters(models.back(), {{name, value}});
            } catch (const Error& e) {
                throw Error(e.message(),
                            {.file = fileOf(p),
                             .parameter = at + "/parameters/" + project::printable(name, 80),
                             .value = e.value(),
                             .validRange = e.validRange()});
            }
        }
    }
    return models;
}

float blockAge(const ProjectBlock& b, const SpeciesModel& model) {
    return b.age ? *b.age : model.recommendedAge;
}

void requireReadable(const Project& p, const std::string& path, const std::string& field,
                     const std::string& what) {
    const std::string full = projectPath(p, path);
    // Without blocking on a FIFO or reading a device, within the size limit of its kind.
    const io::InputKind kind = what.find("attraction") != std::string::npos ? io::kAttractionFile
                               : what.find("weather") != std::string::npos  ? io::kWeatherFile
                               : what.find("skeleton") != std::string::npos
                                   ? io::InputKind{"skeleton file", 256 * io::kMiB}
                                   : io::kOBJFile.named("obstacle file");
    try {
        io::checkInputFile(full, kind);
    } catch (const Error& e) {
        throw Error(e.message(), {.file = fileOf(p), .parameter = field, .value = full});
    }
}

ObjectID addGround(Context& ctx, const ProjectGround& g) {
    const vec2 h = 0.5f * g.size;
    Mesh m;
    m.positions = {vec3(g.center.x - h.x, g.center.y - h.y, 0.0f),
                   vec3(g.center.x + h.x, g.center.y - h.y, 0.0f),
                   vec3(g.center.x + h.x, g.center.y + h.y, 0.0f),
                   vec3(g.center.x - h.x, g.center.y + h.y, 0.0f)};
    m.uvs = {vec2(0.0f, 0.0f), vec2(1.0f, 0.0f), vec2(1.0f, 1.0f), vec2(0.0f, 1.0f)};
    m.indices = {0, 1, 2, 0, 2, 3};
    const ObjectID id = ctx.addObject(m, Material{vec3(0.42f, 0.38f, 0.33f), "", "ground"});
    ctx.setObjectData(id, "organ", std::string("ground"));
    return id;
}

// Every plant and object removed and collision avoidance off: the scene as it was.
void clearScene(PlantArchitecture& arch) {
    for (unsigned id : arch.getAllPlantIDs()) arch.deletePlantInstance(id);
    Context& ctx = arch.context();
    const std::vector<ObjectID> left = ctx.objectIDs();
    ctx.deleteObjects(left);
    arch.disableSoftCollisionAvoidance();
    arch.disableSolidObstacleAvoidance();
    arch.disableAttractionPoints();
    arch.setProgressCallback({});
}

// Progress of one block, its stage named after it: "block A (2 of 3): growing".
ProgressCallback blockProgress(const ProgressCallback& progress, const Project& p, std::size_t i) {
    if (!progress) return {};
    const std::string prefix = "block " + p.blocks[i].name + " (" + std::to_string(i + 1) + " of " +
                               std::to_string(p.blocks.size()) + "): ";
    return [progress, prefix](std::string_view stage, double fraction) {
        progress(prefix + std::string(stage), fraction);
    };
}

// A skeleton block's skeleton file, read (its errors name that file and line) and moved by
// the block's origin.
Skeleton readBlockSkeleton(const Project& p, std::size_t i) {
    const ProjectBlock& b = p.blocks[i];
    const std::string field = "blocks/" + std::to_string(i) + "/skeleton/file";
    requireReadable(p, b.skeleton, field, "a skeleton file");
    Skeleton s;
    try {
        s = readSkeletonFile(projectPath(p, b.skeleton));
    } catch (const Error&) {
        rethrowAt(p, field);
    }
    for (SkeletonNode& n : s.nodes) n.position += b.origin / b.skeletonUnit;
    return s;
}

// The canopy a grid or scatter block is.
CanopyOptions blockCanopy(const ProjectBlock& b) {
    CanopyOptions o;
    o.layout = b.layout == ProjectBlock::Layout::Grid ? CanopyOptions::Layout::Grid
                                                      : CanopyOptions::Layout::Scatter;
    o.center = b.origin;
    o.spacing = b.spacing;
    o.count = b.count;
    o.extent = b.area;
    o.plants = b.plants;
    o.germinationRate = b.germination;
    o.buildParameters = b.parameters;
    return o;
}

// `only`: the block's plants to build (absent: all of them).
std::vector<unsigned> buildBlock(const Project& p, std::size_t i, float age,
                                 const SpeciesModel& model, PlantArchitecture& arch,
                                 const std::optional<std::vector<unsigned>>& only) {
    const ProjectBlock& b = p.blocks[i];
    const std::string at = "blocks/" + std::to_string(i);
    if (only && b.layout == ProjectBlock::Layout::Skeleton)
        throw Error("a skeleton block is not built in part",
                    {.file = fileOf(p),
                     .parameter = at + "/layout",
                     .value = "skeleton",
                     .validRange = "grid, scatter or single, or every plant of the project"});
    try {
        if (b.bend || b.elasticModulus || !b.speciesParameters.empty()) {
            // The block's mechanics and species fields on the species as loaded (its edits
            // made by loadBlockSpecies): its plants bend as they grow.
            SpeciesModel bent = model;
            if (b.bend) bent.phenology.mechanics.enabled = true;
            if (b.elasticModulus) bent.phenology.mechanics.elastic_modulus = *b.elasticModulus;
            arch.loadPlantModel(bent);
        } else {
            arch.loadPlantModelFromLibrary(projectSpecies(p, b));
        }
    } catch (const Error&) {
        rethrowAt(p, at + "/species");
    }
    arch.setSeed(b.seed.value_or(p.seed));
    arch.restartPlantStreams();
    arch.setTrellisGeometry(b.trellis && b.layout != ProjectBlock::Layout::Skeleton);
    if (b.layout == ProjectBlock::Layout::Skeleton) {
        const Skeleton skeleton = readBlockSkeleton(p, i);
        std::vector<unsigned> ids;
        try {
            ReconstructOptions o;
            o.age = age;
            o.unit = b.skeletonUnit;
            o.spacing = b.skeletonSpacing;
            ids = reconstructPlants(arch, skeleton, o);
        } catch (const Error&) {
            rethrowAt(p, at + "/skeleton/file");
        }
        try {
            // Rebuilt, not grown: bent now when the species (or the block) bends.
            for (unsigned id : ids)
                if (arch.plant(id).phenology.mechanics.enabled) bendPlant(arch, id);
        } catch (const Error&) {
            rethrowAt(p, at);
        }
        return ids;
    }
    try {
        if (b.layout == ProjectBlock::Layout::Single) {
            if (only && only->empty()) {
                arch.context().reservePlantIDs(1);  // its ID, as when built
                return {};
            }
            if (only && *only != std::vector<unsigned>{0})
                throw Error("a single block has one plant",
                            {.parameter = "only", .validRange = "plant 0 or none"});
            return {arch.buildPlantInstanceFromLibrary(b.origin, age, b.parameters)};
        }
        CanopyOptions o = blockCanopy(b);
        o.only = only;
        return arch.buildPlantCanopyFromLibrary(o, age);
    } catch (const Error&) {
        rethrowAt(p, at);
    }
}

// Ground, obstacles, avoidance and attraction points, as the project enables them.
void buildSurroundings(const Project& p, PlantArchitecture& arch, BuiltProject& built) {
    Context& ctx = arch.context();
    if (p.ground) built.ground.push_back(addGround(ctx, *p.ground));
    for (std::size_t i = 0; i < p.obstacleFiles.size(); ++i) {
        try {
            const auto ids = readObstacleMesh(ctx, projectPath(p, p.obstacleFiles[i]));
            built.obstacles.insert(built.obstacles.end(), ids.begin(), ids.end());
        } catch (const Error&) {
            rethrowAt(p, "obstacles/files/" + std::to_string(i));
        }
    }
    try {
        if (!built.obstacles.empty()) {
            SolidObstacleOptions o;
            o.obstacles = built.obstacles;
            o.avoidanceDistance = p.avoidDistance;
            o.fruitAdjustment = p.fruitAdjustment;
            arch.enableSolidObstacleAvoidance(o);
        }
    } catch (const Error&) {
        rethrowAt(p, "obstacles");
    }
    try {
        if (p.softCollision) {
            SoftCollisionOptions o;
            o.cone = p.softCone;
            arch.enableSoftCollisionAvoidance(o);
        }
    } catch (const Error&) {
        rethrowAt(p, "soft_collision/cone");
    }
    if (p.attraction) {
        AttractionPoints a;
        a.points = p.attractionPoints;
        if (!p.attractionFile.empty()) {
            const auto more =
                readAttractionPointsCSV(projectPath(p, p.attractionFile), "attraction/file");
            a.points.insert(a.points.end(), more.begin(), more.end());
        }
        if (a.points.empty())
            throw Error("attraction is enabled but there are no points",
                        {.file = fileOf(p),
                         .parameter = "attraction/enabled",
                         .validRange = "points or a file of them, or false"});
        a.halfAngle = p.attractionCone.halfAngle;
        a.lookAhead = p.attractionCone.lookAhead;
        a.inertia = p.attractionCone.inertia;
        try {
            arch.enableAttractionPoints(a);
        } catch (const Error&) {
            rethrowAt(p, "attraction/cone");
        }
    }
}

// The season of the project's physiology, its weather read: checked, and no block younger than
// its days.
PhysiologySeason projectSeason(const Project& p, const std::vector<SpeciesModel>& models) {
    const ProjectPhysiology& ph = *p.physiology;
    PhysiologySeason s = ph.season;
    if (!ph.weatherFile.empty()) {
        requireReadable(p, ph.weatherFile, "physiology/weather", "a weather file");
        try {
            s.weather = readWeatherFile(projectPath(p, ph.weatherFile));
        } catch (const Error&) {
            rethrowAt(p, "physiology/weather");
        }
        std::size_t dates = 0;
        for (std::size_t i = 0; i < s.weather.size(); ++i) {
            const UTCTime& t = s.weather[i].time;
            const UTCTime& u = s.weather[i == 0 ? 0 : i - 1].time;
            if (i == 0 || t.day != u.day || t.month != u.month || t.year != u.year) ++dates;
        }
        if (dates < ph.days)
            throw Error("the weather has " + std::to_string(dates) + " date(s)",
                        {.file = fileOf(p),
                         .parameter = "physiology/weather",
                         .value = projectPath(p, ph.weatherFile),
                         .validRange = "a date of weather for each of the " +
                                       std::to_string(ph.days) + " days"});
    }
    try {
        checkPhysiologySeason(s);
    } catch (const Error&) {
        rethrowAt(p, "physiology");
    }
    for (std::size_t i = 0; i < p.blocks.size(); ++i)
        if (double(blockAge(p.blocks[i], models[i])) < double(ph.days))
            throw Error(
                "younger than the physiology's days",
                {.file = fileOf(p),
                 .parameter = "blocks/" + std::to_string(i) + "/age",
                 .value = text::formatFloat(blockAge(p.blocks[i], models[i])),
                 .validRange = ">= physiology/days (" + std::to_string(ph.days) + " days)"});
    return s;
}

}  // namespace

std::vector<unsigned> BuiltProject::plants() const {
    std::vector<unsigned> all;
    for (const auto& block : blockPlants) all.insert(all.end(), block.begin(), block.end());
    return all;
}

std::vector<vec3> projectBlockPositions(const Project& p, std::size_t i) {
    if (i >= p.blocks.size())
        throw Error("no such block", {.file = fileOf(p),
                                      .parameter = "blocks",
                                      .value = std::to_string(i),
                                      .validRange = "0 to " + std::to_string(p.blocks.size())});
    const ProjectBlock& b = p.blocks[i];
    const std::string at = "blocks/" + std::to_string(i);
    if (b.layout == ProjectBlock::Layout::Single) return {b.origin};
    if (b.layout == ProjectBlock::Layout::Skeleton)
        throw Error("a skeleton block's plants are placed by building it",
                    {.file = fileOf(p),
                     .parameter = at + "/layout",
                     .value = "skeleton",
                     .validRange = "grid, scatter or single"});
    try {
        return canopyPositions(blockCanopy(b), b.seed.value_or(p.seed));
    } catch (const Error&) {
        rethrowAt(p, at);
    }
}

std::string projectPath(const Project& project, const std::string& path) {
    const std::filesystem::path p(path);
    if (path.empty() || p.is_absolute() || project.folder.empty() || project.folder == ".")
        return path;
    return (std::filesystem::path(project.folder) / p).string();
}

std::string projectSpecies(const Project& project, const ProjectBlock& block) {
    return isSpeciesPath(block.species) ? projectPath(project, block.species) : block.species;
}

void checkProject(const Project& p) {
    loadBlockSpecies(p);
    for (std::size_t i = 0; i < p.blocks.size(); ++i)
        if (p.blocks[i].layout == ProjectBlock::Layout::Skeleton) readBlockSkeleton(p, i);
    for (std::size_t i = 0; i < p.obstacleFiles.size(); ++i) {
        const std::string field = "obstacles/files/" + std::to_string(i);
        requireReadable(p, p.obstacleFiles[i], field, "an obstacle file");
        Context scratch;
        try {
            readObstacleMesh(scratch, projectPath(p, p.obstacleFiles[i]));
        } catch (const Error&) {
            rethrowAt(p, field);
        }
    }
    if (!p.attractionFile.empty()) {
        requireReadable(p, p.attractionFile, "attraction/file", "an attraction point file");
        readAttractionPointsCSV(projectPath(p, p.attractionFile), "attraction/file");
    }
    if (p.physiology) projectSeason(p, loadBlockSpecies(p));
}

BuiltProject buildProject(const Project& p, PlantArchitecture& arch,
                          const ProjectBuildOptions& options) {
    if (!arch.getAllPlantIDs().empty() || arch.context().objectCount() != 0)
        throw Error("a project is built into an empty scene",
                    {.file = fileOf(p),
                     .validRange = "a PlantArchitecture and Context without "
                                   "plants or objects"});
    const std::vector<SpeciesModel> models = loadBlockSpecies(p);
    std::optional<PhysiologySeason> season;
    if (p.physiology) season = projectSeason(p, models);
    const float seasonDays = p.physiology ? float(p.physiology->days) : 0.0f;
    BuiltProject built;
    try {
        arch.setTriangleLimit(options.maxTriangles);
        arch.setMeshDetail(p.meshDetail);
        buildSurroundings(p, arch, built);
        for (std::size_t i = 0; i < p.blocks.size(); ++i) {
            arch.setProgressCallback(blockProgress(options.progress, p, i));
            std::optional<std::vector<unsigned>> only;
            if (options.only) {
                if (options.only->size() != p.blocks.size())
                    throw Error("one list of plants per block",
                                {.file = fileOf(p),
                                 .parameter = "blocks",
                                 .value = std::to_string(options.only->size()) + " lists",
                                 .validRange = std::to_string(p.blocks.size()) + " lists"});
                only = (*options.only)[i];
            }
            built.blockPlants.push_back(buildBlock(
                p, i, blockAge(p.blocks[i], models[i]) - seasonDays, models[i], arch, only));
        }
        arch.setProgressCallback({});
        if (season) {
            try {
                built.physiology = growPhysiologySeason(arch, built.plants(), *season,
                                                        p.physiology->days, options.progress);
            } catch (const Error&) {
                rethrowAt(p, "physiology");
            }
        }
        arch.setSeed(p.seed);
    } catch (...) {
        clearScene(arch);
        throw;
    }
    return built;
}

std::vector<double> projectGrowth(const Project& earlier, const Project& later) {
    if (earlier.physiology || later.physiology)
        throw Error("a project with a physiology season is built again, not grown on",
                    {.file = fileOf(later),
                     .parameter = "physiology",
                     .validRange = "a project without physiology"});
    // Only the ages may differ.
    auto withoutAges = [](Project p) {
        for (ProjectBlock& b : p.blocks) b.age.reset();
        return p;
    };
    const Project a = withoutAges(earlier), b = withoutAges(later);
    if (a.blocks.size() != b.blocks.size())
        throw Error("growing on needs the same blocks",
                    {.file = fileOf(later),
                     .parameter = "blocks",
                     .value = std::to_string(later.blocks.size()) + " blocks",
                     .validRange = std::to_string(earlier.blocks.size()) + " blocks, as built"});
    Project aTop = a, bTop = b;
    aTop.blocks.clear();
    bTop.blocks.clear();
    if (writeProjectString(aTop) != writeProjectString(bTop))
        throw Error("growing on changes only block ages",
                    {.file = fileOf(later), .validRange = "the project as built, ages later"});
    for (std::size_t i = 0; i < a.blocks.size(); ++i) {
        Project x, y;
        x.blocks = {a.blocks[i]};
        y.blocks = {b.blocks[i]};
        if (writeProjectString(x) != writeProjectString(y))
            throw Error("growing on changes only block ages",
                        {.file = fileOf(later),
                         .parameter = "blocks/" + std::to_string(i),
                         .validRange = "the block as built, its age later"});
    }
    const std::vector<SpeciesModel> models = loadBlockSpecies(later);
    std::vector<double> days;
    for (std::size_t i = 0; i < later.blocks.size(); ++i) {
        const float from = blockAge(earlier.blocks[i], models[i]);
        const float to = blockAge(later.blocks[i], models[i]);
        if (!(to >= from))
            throw Error("earlier than the plants' age",
                        {.file = fileOf(later),
                         .parameter = "blocks/" + std::to_string(i) + "/age",
                         .value = text::formatFloat(to),
                         .validRange = ">= " + text::formatFloat(from) + " days (as built)"});
        days.push_back(double(to) - double(from));
    }
    return days;
}

void growProject(const Project& earlier, const Project& later, PlantArchitecture& arch,
                 const BuiltProject& built, const ProjectBuildOptions& options) {
    const std::vector<double> days = projectGrowth(earlier, later);
    if (built.blockPlants.size() != days.size())
        throw Error("growing on needs the plants of every block",
                    {.file = fileOf(later),
                     .parameter = "blocks",
                     .validRange = std::to_string(days.size()) + " blocks, as built"});
    struct Reset {
        PlantArchitecture& arch;
        ~Reset() { arch.setProgressCallback({}); }
    } reset{arch};
    arch.setTriangleLimit(options.maxTriangles);
    // Plants that grow by the same days grow together (with soft avoidance they see each
    // other as they grow); otherwise block by block.
    if (std::all_of(days.begin(), days.end(), [&](double d) { return d == days.front(); })) {
        arch.setProgressCallback(options.progress);
        if (!days.empty() && days.front() > 0.0) arch.advanceTime(built.plants(), days.front());
        return;
    }
    for (std::size_t i = 0; i < days.size(); ++i) {
        arch.setProgressCallback(blockProgress(options.progress, later, i));
        if (days[i] > 0.0) arch.advanceTime(built.blockPlants[i], days[i]);
    }
}

ProjectStats projectStats(const PlantArchitecture& arch, const BuiltProject& built) {
    ProjectStats s;
    const Context& ctx = arch.context();
    s.triangles = ctx.triangleCount();
    s.objects = ctx.objectCount();
    for (unsigned id : built.plants()) {
        ++s.plants;
        s.height = std::max(s.height, arch.getPlantHeight(id));
        s.leafArea += arch.getPlantLeafArea(id);
        s.leafCount += arch.getPlantLeafCount(id);
    }
    return s;
}

}  // namespace plantarch
