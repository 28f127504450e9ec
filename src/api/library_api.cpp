// PlantArchitecture's species-library methods: loading a species, building plants from it,
// and reading or changing the current shoot parameters.

#include "api/facade_impl.h"
#include "plantarch/Error.h"
#include "plantarch/SpeciesIO.h"

namespace plantarch {

void PlantArchitecture::loadPlantModelFromLibrary(const std::string& nameOrPath) {
    auto model = std::make_shared<SpeciesModel>(loadSpecies(nameOrPath));
    // Validate everything before replacing anything: a failed load leaves the old model.
    for (const auto& [label, params] : model->shootTypes) {
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
    const unsigned id = buildPlantStructure(base_position, build_parameters);
    try {
        advanceTime(id, age);
    } catch (...) {
        deletePlantInstance(id);
        throw;
    }
    return id;
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
                id, speciesAttractionPoints(model, seed(), id, base_position, build_parameters));
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
