// PlantArchitecture: construction, shoot types, plants and shoots built by hand.

#include <cmath>
#include <filesystem>

#include "api/facade_impl.h"
#include "collision/collision_world.h"
#include "core/value_text.h"
#include "geometry/builtin_prototypes.h"
#include "geometry/tessellate.h"
#include "growth/growth.h"
#include "plantarch/Error.h"
#include "plantarch/OrganLibrary.h"
#include "plantarch/OrganPrototypes.h"

namespace plantarch {

// ---- shoot type checks -------------------------------------------------------------------

void checkFunctions(const FunctionRegistry& functions, const ShootParameters& params,
                    const std::string& label) {
    const auto& ph = params.phytomer_parameters;
    auto list = [](const auto& registry) {
        std::string names;
        for (const auto& [name, fn] : registry) names += (names.empty() ? "" : ", ") + name;
        return "one of: " + names;
    };
    auto checkFile = [&](const std::string& file, const std::string& field) {
        if (!std::filesystem::is_regular_file(file))
            throw Error("OBJ model file not found", {.file = file,
                                                     .parameter = label + ".phytomer." + field,
                                                     .value = file,
                                                     .validRange = "an existing .obj file"});
    };
    if (!ph.leaf.prototype.OBJ_model_file.empty())
        checkFile(ph.leaf.prototype.OBJ_model_file, "leaf.prototype.OBJ_model_file");
    const std::string& leafFn = ph.leaf.prototype.prototype_function;
    if (!functions.leafPrototypes.count(leafFn))
        throw Error("unknown leaf prototype function",
                    {.parameter = label + ".phytomer.leaf.prototype.prototype_function",
                     .value = leafFn,
                     .validRange = list(functions.leafPrototypes)});
    if (!ph.phytomer_creation_function.empty() &&
        !functions.creationFunctions.count(ph.phytomer_creation_function))
        throw Error("unknown phytomer creation function",
                    {.parameter = label + ".phytomer.phytomer_creation_function",
                     .value = ph.phytomer_creation_function,
                     .validRange = list(functions.creationFunctions)});
    if (!ph.phytomer_callback_function.empty() &&
        !functions.callbackFunctions.count(ph.phytomer_callback_function))
        throw Error("unknown phytomer callback function",
                    {.parameter = label + ".phytomer.phytomer_callback_function",
                     .value = ph.phytomer_callback_function,
                     .validRange = list(functions.callbackFunctions)});
    for (const auto& [field, name] :
         {std::pair{"flower_prototype_function", ph.inflorescence.flower_prototype_function},
          std::pair{"fruit_prototype_function", ph.inflorescence.fruit_prototype_function}})
        if (isOBJPrototypeName(name))
            checkFile(name, std::string("inflorescence.") + field);
        else if (isFloralFamily(name)) {
            const bool fruit = std::string(field).rfind("fruit", 0) == 0;
            try {
                validateFloralParameters(name, fruit
                                                   ? ph.inflorescence.fruit_prototype_parameters
                                                   : ph.inflorescence.flower_prototype_parameters);
            } catch (const Error& e) {
                throw e.withParameterPrefix(label + ".phytomer.inflorescence." +
                                            (fruit ? "fruit" : "flower") + "_prototype_parameters");
            }
        } else if (!name.empty() && !functions.floralPrototypes.count(name))
            throw Error("unknown flower/fruit prototype function",
                        {.parameter = label + ".phytomer.inflorescence." + field,
                         .value = name,
                         .validRange = list(functions.floralPrototypes)});
}

// ---- construction, shoot types, plants and shoots --------------------------------------

PlantArchitecture::PlantArchitecture(Context* context)
    : context_(context), impl_(std::make_unique<Impl>()) {
    if (!context) throw Error("PlantArchitecture needs a Context", {.parameter = "context"});
    BuiltinPrototypes builtin = builtinPrototypes();
    for (auto& [name, fn] : builtin.leaves) registerLeafPrototype(name, std::move(fn));
    for (auto& [name, fn] : builtin.floral) registerFloralPrototype(name, std::move(fn));
    // The library's own functions: the same in every PlantArchitecture, so their shapes are
    // shared by all of them (PrototypeCache).
    impl_->functions.userLeafPrototypes.clear();
    impl_->functions.userFloralPrototypes.clear();
}

PlantArchitecture::~PlantArchitecture() = default;

void PlantArchitecture::setSeed(std::uint64_t seed) {
    seed_ = seed;
}

void PlantArchitecture::restartPlantStreams() {
    impl_->store.nextStream = 0;
}

unsigned PlantArchitecture::plantStream(unsigned plantID) const {
    return impl_->store.plant(plantID).stream;
}

void PlantArchitecture::defineShootType(const std::string& label, const ShootParameters& params) {
    if (label.empty())
        throw Error("shoot type label must not be empty", {.parameter = "shoot_type_label"});
    validate(params, label);
    checkFunctions(impl_->functions, params, label);
    impl_->store.shootTypes[label] = params;
}

const ShootParameters& PlantArchitecture::shootType(const std::string& label) const {
    auto it = impl_->store.shootTypes.find(label);
    if (it == impl_->store.shootTypes.end()) {
        std::string valid;
        for (const auto& [known, p] : impl_->store.shootTypes)
            valid += (valid.empty() ? "one of: " : ", ") + known;
        throw Error("unknown shoot type",
                    {.parameter = "shoot_type_label",
                     .value = label,
                     .validRange = valid.empty() ? "none defined yet: load a species or "
                                                   "defineShootType first"
                                                 : valid});
    }
    return it->second;
}

std::vector<std::string> PlantArchitecture::listShootTypeLabels() const {
    std::vector<std::string> labels;
    for (const auto& [label, p] : impl_->store.shootTypes) labels.push_back(label);
    return labels;
}

std::vector<std::string> PlantArchitecture::listShootTypeLabels(unsigned plantID) const {
    std::vector<std::string> labels;
    for (const auto& [label, p] : impl_->store.plant(plantID).shootTypes) labels.push_back(label);
    return labels;
}

unsigned PlantArchitecture::addPlantInstance(const vec3& base_position, float current_age) {
    if (!std::isfinite(base_position.x) || !std::isfinite(base_position.y) ||
        !std::isfinite(base_position.z))
        throw Error("plant base position must be finite", {.parameter = "base_position"});
    if (!(current_age >= 0.0f && std::isfinite(current_age)))
        throw Error("invalid plant age", {.parameter = "current_age",
                                          .value = text::formatFloat(current_age),
                                          .validRange = ">= 0 days"});
    PlantInstance p;
    PlantStore& store = impl_->store;
    p.id = store.assignedID ? *store.assignedID : context_->reservePlantIDs(1);
    store.assignedID.reset();
    p.stream = store.nextStream++;
    p.base = base_position;
    p.age = current_age;
    p.rng = Rng::forPlant(seed_, p.stream);
    p.shootTypes = impl_->store.shootTypes;
    p.phenology = impl_->store.defaultPhenology;
    p.groundClearance = impl_->store.groundClearance;
    p.nextDormancyBreak = p.phenology.time_to_dormancy_break < 0.0f
                              ? -1.0
                              : p.age + p.phenology.time_to_dormancy_break;
    return impl_->store.plants.emplace(p.id, std::move(p)).first->first;
}

void PlantArchitecture::deletePlantInstance(unsigned plantID) {
    PlantInstance& p = impl_->store.plant(plantID);
    for (Shoot& s : p.shoots) deleteShootObjects(*context_, s);
    impl_->store.plants.erase(plantID);
    if (const auto t = impl_->trellis.find(plantID); t != impl_->trellis.end()) {
        for (ObjectID id : t->second)
            if (context_->doesObjectExist(id)) context_->deleteObject(id);
        impl_->trellis.erase(t);
    }
    impl_->collision.attractionIndexes.erase(plantID);
    if (impl_->collision.world) impl_->collision.world->removePlant(plantID);
}

unsigned PlantArchitecture::addBaseStemShoot(unsigned plantID, const ShootSpec& spec) {
    PlantInstance& p = impl_->store.plant(plantID);
    if (!p.shoots.empty())
        throw Error("the plant already has a base stem",
                    {.parameter = "plantID", .value = std::to_string(plantID)});
    const unsigned id = createShoot(impl_->growth(), p, spec, StartMode::Base, -1, 0, 0);
    updateGeometry(plantID);
    return id;
}

unsigned PlantArchitecture::appendShoot(unsigned plantID, unsigned parentShootID,
                                        const ShootSpec& spec) {
    PlantInstance& p = impl_->store.plant(plantID);
    PlantStore::shoot(p, parentShootID);
    const unsigned id =
        createShoot(impl_->growth(), p, spec, StartMode::Append, int(parentShootID), 0, 0);
    updateGeometry(plantID);
    return id;
}

unsigned PlantArchitecture::addChildShoot(unsigned plantID, unsigned parentShootID,
                                          unsigned parentNode, const ShootSpec& spec,
                                          unsigned petioleIndex) {
    PlantInstance& p = impl_->store.plant(plantID);
    PlantStore::shoot(p, parentShootID);
    const unsigned id = createShoot(impl_->growth(), p, spec, StartMode::Child, int(parentShootID),
                                    parentNode, petioleIndex);
    updateGeometry(plantID);
    return id;
}

unsigned PlantArchitecture::addEpicormicShoot(unsigned plantID, unsigned parentShootID,
                                              float position, const ShootSpec& spec) {
    PlantInstance& p = impl_->store.plant(plantID);
    const Shoot& parent = PlantStore::shoot(p, parentShootID);
    if (!(position > 0.0f && position <= 1.0f))
        throw Error("position along the parent shoot out of range",
                    {.parameter = "position",
                     .value = std::to_string(position),
                     .validRange = "> 0 and <= 1 (a fraction of its length)"});
    if (parent.phytomers.empty())
        throw Error("the parent shoot has no phytomers",
                    {.parameter = "parentShootID", .value = std::to_string(parentShootID)});
    const unsigned id = createShoot(impl_->growth(), p, spec, StartMode::Epicormic,
                                    int(parentShootID), epicormicNode(parent, position), 0);
    updateGeometry(plantID);
    return id;
}

unsigned PlantArchitecture::appendPhytomerToShoot(unsigned plantID, unsigned shootID,
                                                  const PhytomerParameters& pp,
                                                  const PhytomerSize& size) {
    PlantInstance& p = impl_->store.plant(plantID);
    Shoot& s = PlantStore::shoot(p, shootID);
    checkPhytomerSize(size);
    validate(pp, "phytomer_parameters");
    ShootParameters probe = impl_->store.shootTypeFor(p, s.type);
    probe.phytomer_parameters = pp;
    checkFunctions(impl_->functions, probe, s.type);
    createPhytomer(impl_->growth(), p, s, pp, size.internodeRadius, size.internodeLengthMax,
                   size.internodeLengthScale, size.leafScale, nullptr);
    s.nodesThisSeason++;
    scheduleNewShoot(impl_->growth(), p, s);
    updateGeometry(plantID);
    return unsigned(s.phytomers.size());
}

}  // namespace plantarch