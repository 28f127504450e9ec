// PlantArchitecture's species-library methods: loading a species, building plants from it,
// and reading or changing the current shoot parameters.

#include <unistd.h>

#include "api/facade_impl.h"
#include "core/value_text.h"
#include "plantarch/Error.h"
#include "plantarch/SpeciesBuild.h"
#include "plantarch/SpeciesIO.h"

namespace plantarch {

namespace {

// A node rule's error while the plant grows (its parameter the rule's path, e.g.
// "stem.phytomer.node_rules[2].leaf_scale") placed at the rule's own line in the species file;
// rethrows any other error as it is.
[[noreturn]] void rethrowAtRuleLine(const Error& e, const SpeciesModel& species) {
    if (e.file().empty() && e.parameter().find(".node_rules[") != std::string::npos) {
        const auto line = species.lines.find(e.parameter());
        if (line != species.lines.end()) throw e.withFile(species.sourceFile, line->second);
    }
    throw;
}

}  // namespace

void PlantArchitecture::loadPlantModelFromLibrary(const std::string& nameOrPath) {
    loadPlantModel(loadSpecies(nameOrPath));
}

void PlantArchitecture::loadPlantModel(const SpeciesModel& species) {
    auto model = std::make_shared<SpeciesModel>(species);
    // Validate everything before replacing anything: a failed load leaves the old model.
    if (const std::vector<Error> bad = checkSpeciesFiles(*model); !bad.empty()) throw bad.front();
    for (const auto& [label, params] : speciesShootTypes(*model)) {
        validate(params, label);
        checkFunctions(impl_->functions, params, label);
    }
    validate(model->phenology, "phenology");
    impl_->store.shootTypes.clear();
    defineSpeciesShootTypes(*this, *model);
    impl_->store.defaultPhenology = model->phenology;
    impl_->species = std::move(model);
}

std::vector<std::string> PlantArchitecture::getAvailablePlantModels() const {
    return listSpecies();
}

std::string PlantArchitecture::getCurrentPlantModel() const {
    return impl_->species ? impl_->species->name : std::string();
}

std::vector<std::string> PlantArchitecture::listShootTypeLabels(
    const std::string& nameOrPath) const {
    std::vector<std::string> labels;
    for (const auto& [label, p] : loadSpecies(nameOrPath).shootTypes) labels.push_back(label);
    return labels;
}

unsigned PlantArchitecture::buildPlantInstanceFromLibrary(
    const vec3& base_position, float age, const std::map<std::string, float>& build_parameters) {
    if (!impl_->species)
        throw Error("no species loaded: call loadPlantModelFromLibrary first",
                    {.parameter = "species", .validRange = "one of the library species"});
    if (!(age >= 0.0f) || !std::isfinite(age))
        throw Error("invalid plant age",
                    {.parameter = "age", .value = std::to_string(age), .validRange = ">= 0 days"});
    resolveBuildParameters(*impl_->species, build_parameters);  // range errors before any change
    if (impl_->trellisGeometry && impl_->species->trellis)      // and the trellis's
        speciesTrellis(*impl_->species, seed(), impl_->store.nextStream, base_position,
                       build_parameters);
    // The plant is drawn once, when grown to its age: its objects are then made in the order
    // of its organs, as reading its file back makes them (and the seedling's geometry, which
    // growing would replace at once, is never made).
    unsigned id;
    {
        struct Defer {
            bool& flag;
            bool was;
            ~Defer() { flag = was; }
        } defer{impl_->geometryDeferred, impl_->geometryDeferred};
        impl_->geometryDeferred = true;
        id = buildPlantStructure(base_position, build_parameters);
    }
    try {
        advanceTime(id, age);
        addTrellis(id, base_position, build_parameters);
    } catch (const Error& e) {
        deletePlantInstance(id);
        rethrowAtRuleLine(e, *impl_->species);
    } catch (...) {
        deletePlantInstance(id);
        throw;
    }
    return id;
}

void PlantArchitecture::setTriangleLimit(std::size_t limit) {
    context_->setTriangleLimit(limit);
    impl_->store.triangleLimit = limit;
}

std::size_t PlantArchitecture::getTriangleLimit() const {
    return context_->triangleLimit();
}

std::size_t PlantArchitecture::defaultTriangleLimit() {
    const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGESIZE);
    if (pages <= 0 || pageSize <= 0) return 0;  // unknown: no limit
    return std::size_t(pages) / 2 * std::size_t(pageSize) / kBytesPerTriangle;
}

void PlantArchitecture::setTrellisGeometry(bool on) {
    impl_->trellisGeometry = on;
}

bool PlantArchitecture::getTrellisGeometry() const {
    return impl_->trellisGeometry;
}

void PlantArchitecture::setMeshDetail(float detail) {
    if (!(detail >= kMinMeshDetail && detail <= kMaxMeshDetail))
        throw Error("out of range", {.parameter = "mesh_detail",
                                     .value = text::formatFloat(detail),
                                     .validRange = "0.1 to 4"});
    if (detail == impl_->store.meshDetail) return;
    impl_->store.meshDetail = detail;
    for (const auto& [id, plant] : impl_->store.plants) updateGeometry(id);
}

float PlantArchitecture::getMeshDetail() const {
    return impl_->store.meshDetail;
}

void PlantArchitecture::setOrganGeometry(OrganKind kind, bool build) {
    const std::size_t k = std::size_t(kind);
    if (k >= kOrganKinds)
        throw Error("unknown organ kind", {.parameter = "kind", .value = std::to_string(k)});
    if (impl_->store.organGeometry[k] == build) return;
    impl_->store.organGeometry[k] = build;
    for (const auto& [id, plant] : impl_->store.plants) updateGeometry(id);
}

bool PlantArchitecture::getOrganGeometry(OrganKind kind) const {
    const std::size_t k = std::size_t(kind);
    if (k >= kOrganKinds)
        throw Error("unknown organ kind", {.parameter = "kind", .value = std::to_string(k)});
    return impl_->store.organGeometry[k];
}

std::vector<ObjectID> PlantArchitecture::getPlantTrellisObjectIDs(unsigned plantID) const {
    impl_->store.plant(plantID);  // an unknown plant is an error
    const auto t = impl_->trellis.find(plantID);
    return t == impl_->trellis.end() ? std::vector<ObjectID>{} : t->second;
}

void PlantArchitecture::addTrellis(unsigned plantID, const vec3& base,
                                   const std::map<std::string, float>& build_parameters) {
    if (!impl_->trellisGeometry || !impl_->species || !impl_->species->trellis) return;
    const SpeciesModel& model = *impl_->species;
    const std::vector<TrellisPart> parts =
        speciesTrellis(model, seed(), impl_->store.plant(plantID).stream, base, build_parameters);
    std::vector<ObjectID>& ids = impl_->trellis[plantID];
    for (const TrellisPart& part : parts) {
        const bool post = part.kind == TrellisPart::Kind::Post;
        const Material m{post ? vec3(0.45f, 0.33f, 0.2f) : vec3(0.3f, 0.3f, 0.32f), "", "trellis"};
        const ObjectID id = context_->addObject(part.mesh, m);
        context_->setObjectData(id, "organ", std::string("trellis"));
        context_->setObjectData(id, "trellis_part", std::string(post ? "post" : "wire"));
        context_->setObjectData(id, "plantID", std::int32_t(plantID));
        context_->setObjectData(id, "plant_name", model.name);
        ids.push_back(id);
    }
}

unsigned PlantArchitecture::buildPlantStructure(
    const vec3& base_position, const std::map<std::string, float>& build_parameters) {
    const SpeciesModel& model = *impl_->species;
    const unsigned id = addPlantInstance(base_position, 0.0f);
    try {
        impl_->store.plant(id).name = model.name;
        buildInitialStructure(*this, id, model, build_parameters);
        if (model.attraction)
            enableAttractionPoints(
                id, speciesAttractionPoints(model, seed(), impl_->store.plant(id).stream,
                                            base_position, build_parameters));
    } catch (...) {
        deletePlantInstance(id);
        throw;
    }
    return id;
}

ShootParameters PlantArchitecture::getCurrentShootParameters(const std::string& label) const {
    return shootType(label);
}

std::map<std::string, ShootParameters> PlantArchitecture::getCurrentShootParameters() const {
    return impl_->store.shootTypes;
}

void PlantArchitecture::updateCurrentShootParameters(const std::string& label,
                                                     const ShootParameters& params) {
    shootType(label);  // must exist: an update never invents a type
    defineShootType(label, params);
}

void PlantArchitecture::updateCurrentShootParameters(
    const std::map<std::string, ShootParameters>& params) {
    for (const auto& [label, p] : params) {
        shootType(label);
        validate(p, label);
        checkFunctions(impl_->functions, p, label);
    }
    for (const auto& [label, p] : params) impl_->store.shootTypes[label] = p;
}

}  // namespace plantarch
