// PlantArchitecture's plant structure methods: XML files and plant strings.

#include <fstream>
#include <set>
#include <sstream>

#include "api/facade_impl.h"
#include "core/atomic_file.h"
#include "io/plant_structure.h"
#include "plantarch/Error.h"
#include "plantarch/HeliosPlantXML.h"

namespace plantarch {

namespace {

plant_io::Defaults defaultsOf(const PlantStore& store, std::uint64_t seed) {
    plant_io::Defaults d;
    d.shootTypes = &store.shootTypes;
    d.phenology = store.defaultPhenology;
    d.seed = seed;
    d.firstPlantID = store.nextPlantID;
    return d;
}

// Shoot types a plant may still ask the PlantArchitecture for (child types defined after the
// plant was made) are added to what is written, so the file needs nothing else.
std::map<std::string, ShootParameters> typesToWrite(const PlantStore& store, const PlantInstance& p,
                                                    bool& changed) {
    std::map<std::string, ShootParameters> types = p.shootTypes;
    std::vector<std::string> pending;
    for (const auto& [label, t] : types) pending.push_back(label);
    for (const Shoot& s : p.shoots) pending.push_back(s.type);
    changed = false;
    while (!pending.empty()) {
        const std::string label = pending.back();
        pending.pop_back();
        if (!types.count(label)) {
            auto global = store.shootTypes.find(label);
            if (global == store.shootTypes.end()) continue;
            types.emplace(label, global->second);
            changed = true;
        }
        for (const auto& [child, prob] : types.at(label).child_shoot_types)
            if (!types.count(child)) pending.push_back(child);
    }
    return types;
}

}  // namespace

std::string PlantArchitecture::getPlantStructureXML(const std::vector<unsigned>& plantIDs) const {
    std::vector<PlantInstance> copies;
    copies.reserve(plantIDs.size());
    std::vector<const PlantInstance*> plants;
    for (unsigned id : plantIDs) {
        const PlantInstance& p = impl_->store.plant(id);
        bool changed = false;
        auto types = typesToWrite(impl_->store, p, changed);
        if (changed) {
            copies.push_back(p);
            copies.back().shootTypes = std::move(types);
            plants.push_back(&copies.back());
        } else {
            plants.push_back(&p);
        }
    }
    return plant_io::writePlantsXML(plants);
}

void PlantArchitecture::writePlantStructureXML(const std::vector<unsigned>& plantIDs,
                                               const std::string& filename) const {
    const std::string text = getPlantStructureXML(plantIDs);
    io::AtomicFile file(filename);
    file.write(text);
    file.commit();
}

void PlantArchitecture::writePlantStructureXML(unsigned plantID,
                                               const std::string& filename) const {
    writePlantStructureXML(std::vector<unsigned>{plantID}, filename);
}

namespace {

// Adds plants read from a file: every named function must be registered; then each plant
// gets the next ID and its geometry. Nothing is added when any check fails.
std::vector<unsigned> adopt(PlantArchitecture& arch, PlantStore& store,
                            const FunctionRegistry& functions, plant_io::ReadResult&& read,
                            const std::string& file, const PlantStructureReadOptions& options) {
    for (std::size_t k = 0; k < read.plants.size(); ++k)
        for (const auto& [label, params] : read.plants[k].shootTypes) {
            try {
                checkFunctions(functions, params, label);
            } catch (const Error& e) {
                throw e.withParameterPrefix("plant_instance[" + std::to_string(k) + "].shoot_type")
                    .withFile(file);
            }
        }
    std::vector<unsigned> ids;
    try {
        for (PlantInstance& p : read.plants) {
            const unsigned id = store.nextPlantID++;
            p.id = id;
            store.plants.emplace(id, std::move(p));
            ids.push_back(id);
            arch.updateGeometry(id);
        }
    } catch (...) {
        for (unsigned id : ids) arch.deletePlantInstance(id);
        throw;
    }
    if (options.onWarning)
        for (const std::string& w : read.warnings) options.onWarning(w);
    return ids;
}

}  // namespace

std::vector<unsigned> PlantArchitecture::readPlantStructureXMLString(
    const std::string& xml, const PlantStructureReadOptions& options) {
    auto read =
        plant_io::readPlantsXML(xml, options.nameForErrors, defaultsOf(impl_->store, seed_));
    return adopt(*this, impl_->store, impl_->functions, std::move(read), options.nameForErrors,
                 options);
}

std::vector<unsigned> PlantArchitecture::readPlantStructureXML(
    const std::string& filename, const PlantStructureReadOptions& options) {
    std::ifstream in(filename, std::ios::binary);
    if (!in) throw Error("cannot open plant structure file", {.file = filename});
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) throw Error("cannot read plant structure file", {.file = filename});
    auto read = plant_io::readPlantsXML(text.str(), filename, defaultsOf(impl_->store, seed_));
    return adopt(*this, impl_->store, impl_->functions, std::move(read), filename, options);
}

std::string PlantArchitecture::getPlantString(unsigned plantID,
                                              const PlantStringOptions& options) const {
    if (options.significantDigits < 0 || options.significantDigits > 6)
        throw Error("significant digits out of range",
                    {.parameter = "significantDigits",
                     .value = std::to_string(options.significantDigits),
                     .validRange = "1 to 6, or 0 for exact values"});
    return plant_io::writePlantString(impl_->store.plant(plantID), options.significantDigits);
}

unsigned PlantArchitecture::generatePlantFromString(const std::string& plantString,
                                                    const PlantStructureReadOptions& options) {
    auto read = plant_io::readPlantString(plantString, defaultsOf(impl_->store, seed_));
    return adopt(*this, impl_->store, impl_->functions, std::move(read), "", options).front();
}

}  // namespace plantarch

namespace plantarch {

std::string getHeliosPlantStructureXML(const PlantArchitecture& arch,
                                       const std::vector<unsigned>& plantIDs) {
    std::vector<const PlantInstance*> plants;
    plants.reserve(plantIDs.size());
    for (unsigned id : plantIDs) plants.push_back(&arch.plant(id));
    return plant_io::writeHeliosPlants(plants);
}

void writeHeliosPlantStructureXML(const PlantArchitecture& arch,
                                  const std::vector<unsigned>& plantIDs,
                                  const std::string& filename) {
    const std::string text = getHeliosPlantStructureXML(arch, plantIDs);
    io::AtomicFile file(filename);
    file.write(text);
    file.commit();
}

}  // namespace plantarch
