// PlantArchitecture's plant structure methods: XML files and plant strings.

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <tuple>
#include <type_traits>

#include "api/facade_impl.h"
#include "core/atomic_file.h"
#include "core/input_file.h"
#include "geometry/tessellate.h"
#include "plant_io/object_table.h"
#include "plant_io/plant_structure.h"
#include "plantarch/Error.h"
#include "plantarch/HeliosPlantXML.h"
#include "plantarch/OutputFormats.h"
#include "plantarch/PlantStructureWrite.h"

namespace plantarch {

namespace {

plant_io::Defaults defaultsOf(const PlantStore& store, std::uint64_t seed) {
    plant_io::Defaults d;
    d.shootTypes = &store.shootTypes;
    d.phenology = store.defaultPhenology;
    d.groundClearance = store.groundClearance;
    d.seed = seed;
    d.firstStream = store.nextStream;
    return d;
}

// Shoot types a plant may still ask the PlantArchitecture for (child types defined after the
// plant was made) are added to what is written, so the file needs nothing else.
std::map<std::string, ShootParameters> typesToWrite(
    const std::map<std::string, ShootParameters>& global, const PlantInstance& p, bool& changed) {
    std::map<std::string, ShootParameters> types = p.shootTypes;
    std::vector<std::string> pending;
    for (const auto& [label, t] : types) pending.push_back(label);
    for (const Shoot& s : p.shoots) pending.push_back(s.type);
    changed = false;
    while (!pending.empty()) {
        const std::string label = pending.back();
        pending.pop_back();
        if (!types.count(label)) {
            auto known = global.find(label);
            if (known == global.end()) continue;
            types.emplace(label, known->second);
            changed = true;
        }
        for (const auto& [child, prob] : types.at(label).child_shoot_types)
            if (!types.count(child)) pending.push_back(child);
    }
    return types;
}

// The document of the plants: each with the shoot types it may still ask for.
std::string structureXML(const std::map<std::string, ShootParameters>& global,
                         const std::vector<const PlantInstance*>& source, bool objectIDs,
                         const std::vector<std::vector<unsigned>>* materialIDs = nullptr) {
    std::vector<PlantInstance> copies;
    copies.reserve(source.size());
    std::vector<const PlantInstance*> plants;
    for (const PlantInstance* p : source) {
        bool changed = false;
        auto types = typesToWrite(global, *p, changed);
        if (changed) {
            copies.push_back(*p);
            copies.back().shootTypes = std::move(types);
            plants.push_back(&copies.back());
        } else {
            plants.push_back(p);
        }
    }
    return plant_io::writePlantsXML(plants, objectIDs, materialIDs);
}

}  // namespace

std::string PlantArchitecture::getPlantStructureXML(const std::vector<unsigned>& plantIDs) const {
    std::vector<const PlantInstance*> plants;
    for (unsigned id : plantIDs) plants.push_back(&impl_->store.plant(id));
    return structureXML(impl_->store.shootTypes, plants, false);
}

void PlantArchitecture::writePlantStructureXML(const std::vector<unsigned>& plantIDs,
                                               const std::string& filename) const {
    requireOutputFormat(filename, {".xml"}, "writePlantStructureXML writes a plant structure file");
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

// The object IDs a file gave each organ (one entry per object member, in
// forEachObjectMember order; none: empty), taken out of the plant: tessellation must never
// reach objects of the target Context by an ID from a file.
using RecordedIDs = std::vector<std::vector<ObjectID>>;

template <class Member>
std::vector<ObjectID> idsOf(const Member& m) {
    if constexpr (std::is_same_v<Member, ObjectID>)
        return m == kNoObject ? std::vector<ObjectID>{} : std::vector<ObjectID>{m};
    else
        return m;
}

template <class Member>
void setIDs(Member& m, const std::vector<ObjectID>& ids) {
    if constexpr (std::is_same_v<Member, ObjectID>)
        m = ids.empty() ? kNoObject : ids.front();
    else
        m = ids;
}

RecordedIDs takeObjectIDs(PlantInstance& p) {
    RecordedIDs r;
    plant_io::forEachObjectMember(p, [&](auto& m) {
        r.push_back(idsOf(m));
        setIDs(m, {});
    });
    return r;
}

void clearObjectIDs(const std::vector<PlantInstance*>& plants) {
    for (PlantInstance* p : plants) plant_io::clearObjectIDs(*p);
}

// At most this many unused IDs are made below the restored ones (each costs a record).
constexpr ObjectID kMaxUnusedIDs = 1u << 20;

// Gives the scratch Context's materials the IDs the file recorded (each plant's materials in
// the order its objects first use them), when those IDs are free in `ctx`: the IDs skipped
// get unused placeholder materials (exports write only the materials objects use). Else the
// materials get the next IDs, in the order the objects are copied.
void restoreMaterialIDs(Context& ctx, const Context& scratch,
                        const std::vector<std::tuple<ObjectID, ObjectID, std::size_t>>& pairs,
                        const std::vector<std::vector<unsigned>>& materialIDs) {
    std::map<unsigned, MaterialID> wanted;  // recorded material ID -> scratch material
    std::map<MaterialID, unsigned> given;   // scratch material -> recorded ID
    std::vector<std::vector<MaterialID>> order(materialIDs.size());
    for (const auto& [recordedID, scratchID, k] : pairs) {
        if (k >= materialIDs.size()) return;
        const MaterialID m = scratch.objectMaterial(scratchID);
        auto& o = order[k];
        if (std::find(o.begin(), o.end(), m) != o.end()) continue;
        o.push_back(m);
        if (o.size() > materialIDs[k].size()) return;
        const unsigned r = materialIDs[k][o.size() - 1];
        if ((given.count(m) && given[m] != r) || (wanted.count(r) && wanted[r] != m)) return;
        given[m] = r;
        wanted[r] = m;
    }
    if (wanted.empty() || wanted.begin()->first < ctx.materialCount()) return;
    for (const auto& [r, m] : wanted) {
        while (ctx.materialCount() < r) {
            Material unused;
            unused.name = "unused_" + std::to_string(ctx.materialCount());
            ctx.addMaterial(unused);
        }
        if (ctx.addMaterial(scratch.material(m)) != r) return;
    }
}

// Makes the plants' objects with the IDs their file recorded: when every recorded ID is free
// (above every ID `ctx` has issued: a Context never issues an ID twice), they leave fewer
// than kMaxUnusedIDs unused below them, and the plants' organs still have the objects the
// file says. The objects are made in a scratch Context and copied in ID order (so materials
// are added in the order of the objects using them); the IDs skipped are issued and deleted.
// Returns false, with no object made and no ID set, when the IDs cannot be restored.
bool restoreObjectIDs(Context& ctx, const PlantStore& store, PrototypeCache& prototypes,
                      const std::vector<PlantInstance*>& plants,
                      const std::vector<RecordedIDs>& recorded,
                      const std::vector<std::vector<unsigned>>& materialIDs) {
    std::vector<ObjectID> all;
    for (const RecordedIDs& r : recorded)
        for (const auto& ids : r) all.insert(all.end(), ids.begin(), ids.end());
    if (all.empty()) return false;
    std::sort(all.begin(), all.end());
    const ObjectID limit = ctx.objectIDLimit();
    if (std::adjacent_find(all.begin(), all.end()) != all.end() || all.front() < limit ||
        all.back() - limit - (all.size() - 1) >= kMaxUnusedIDs)
        return false;
    Context scratch;
    std::vector<std::tuple<ObjectID, ObjectID, std::size_t>> pairs;  // recorded, scratch, plant
    bool same = true;
    try {
        for (std::size_t k = 0; k < plants.size(); ++k) {
            tessellatePlant(store, prototypes, scratch, *plants[k]);
            std::size_t i = 0;
            plant_io::forEachObjectMember(*plants[k], [&](auto& m) {
                const std::vector<ObjectID> now = idsOf(m);
                if (i >= recorded[k].size() || recorded[k][i].size() != now.size()) {
                    same = false;
                } else {
                    for (std::size_t j = 0; j < now.size(); ++j)
                        pairs.emplace_back(recorded[k][i][j], now[j], k);
                }
                ++i;
            });
            same = same && i == recorded[k].size();
        }
    } catch (...) {
        clearObjectIDs(plants);
        throw;
    }
    clearObjectIDs(plants);
    if (!same) return false;
    std::sort(pairs.begin(), pairs.end());
    restoreMaterialIDs(ctx, scratch, pairs, materialIDs);
    for (std::size_t a = 0; a < pairs.size();) {
        std::vector<ObjectID> unused;
        while (ctx.objectIDLimit() < std::get<0>(pairs[a])) unused.push_back(ctx.addObject(Mesh{}));
        ctx.deleteObjects(unused);
        std::size_t b = a + 1;
        while (b < pairs.size() && std::get<0>(pairs[b]) == std::get<0>(pairs[b - 1]) + 1) ++b;
        std::vector<ObjectID> from;
        for (std::size_t i = a; i < b; ++i) from.push_back(std::get<1>(pairs[i]));
        const ObjectSource source{&scratch, from};
        ctx.appendObjects({&source, 1});
        a = b;
    }
    for (std::size_t k = 0; k < plants.size(); ++k) {
        std::size_t i = 0;
        plant_io::forEachObjectMember(*plants[k], [&](auto& m) { setIDs(m, recorded[k][i++]); });
    }
    return true;
}

// Adds plants read from a file: every named function must be registered; then each plant
// gets the next ID and its geometry, with the object IDs the file gives where they can be
// restored (restoreObjectIDs). Nothing is added when any check fails.
std::vector<unsigned> adopt(PlantArchitecture& arch, PlantStore& store,
                            const FunctionRegistry& functions, PrototypeCache& prototypes,
                            bool geometryDeferred, plant_io::ReadResult&& read,
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
    // Water sprouts of a type neither the plant nor the PlantArchitecture defines would stop
    // growth later: refused now.
    for (std::size_t k = 0; k < read.plants.size(); ++k)
        if (const auto& e = read.plants[k].epicormic) {
            try {
                store.shootTypeFor(read.plants[k], e->shootType);
            } catch (const Error& err) {
                throw err
                    .withParameterPrefix("plant_instance[" + std::to_string(k) +
                                         "].epicormic_shoots")
                    .withFile(file);
            }
        }
    std::vector<RecordedIDs> recorded;
    for (PlantInstance& p : read.plants) recorded.push_back(takeObjectIDs(p));
    std::vector<unsigned> ids;
    try {
        std::vector<PlantInstance*> added;
        unsigned next = arch.context().reservePlantIDs(unsigned(read.plants.size()));
        store.nextStream += unsigned(read.plants.size());
        for (PlantInstance& p : read.plants) {
            const unsigned id = next++;
            p.id = id;
            added.push_back(&store.plants.emplace(id, std::move(p)).first->second);
            ids.push_back(id);
        }
        if (!geometryDeferred)
            restoreObjectIDs(arch.context(), store, prototypes, added, recorded, read.materialIDs);
        for (unsigned id : ids) arch.updateGeometry(id);
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
    return adopt(*this, impl_->store, impl_->functions, impl_->prototypes, impl_->geometryDeferred,
                 std::move(read), options.nameForErrors, options);
}

std::vector<unsigned> PlantArchitecture::readPlantStructureXML(
    const std::string& filename, const PlantStructureReadOptions& options) {
    auto read = plant_io::readPlantsXML(io::readWholeFile(filename, io::kPlantFile), filename,
                                        defaultsOf(impl_->store, seed_));
    return adopt(*this, impl_->store, impl_->functions, impl_->prototypes, impl_->geometryDeferred,
                 std::move(read), filename, options);
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
    return adopt(*this, impl_->store, impl_->functions, impl_->prototypes, impl_->geometryDeferred,
                 std::move(read), "", options)
        .front();
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
    requireOutputFormat(filename, {".xml", ".helios.xml"},
                        "writeHeliosPlantStructureXML writes a plant structure file");
    const std::string text = getHeliosPlantStructureXML(arch, plantIDs);
    io::AtomicFile file(filename);
    file.write(text);
    file.commit();
}

}  // namespace plantarch

namespace plantarch {

std::string getPlantStructureXML(const PlantArchitecture& arch,
                                 const std::vector<unsigned>& plantIDs,
                                 const PlantStructureWriteOptions& options) {
    std::vector<const PlantInstance*> plants;
    for (unsigned id : plantIDs) plants.push_back(&arch.plant(id));
    // Each plant's materials, in the order its objects (by ID) first use them.
    const Context& ctx = const_cast<PlantArchitecture&>(arch).context();
    std::vector<std::vector<unsigned>> materials;
    if (options.objectIDs)
        for (const PlantInstance* p : plants) {
            std::vector<ObjectID> objects;
            plant_io::forEachObjectMember(*p, [&](const auto& m) {
                for (ObjectID o : idsOf(m))
                    if (ctx.doesObjectExist(o)) objects.push_back(o);
            });
            std::sort(objects.begin(), objects.end());
            std::vector<unsigned> used;
            for (ObjectID o : objects) {
                const MaterialID m = ctx.objectMaterial(o);
                if (std::find(used.begin(), used.end(), m) == used.end()) used.push_back(m);
            }
            materials.push_back(std::move(used));
        }
    return structureXML(arch.getCurrentShootParameters(), plants, options.objectIDs, &materials);
}

void writePlantStructureXML(const PlantArchitecture& arch, const std::vector<unsigned>& plantIDs,
                            const std::string& filename,
                            const PlantStructureWriteOptions& options) {
    requireOutputFormat(filename, {".xml"}, "writePlantStructureXML writes a plant structure file");
    const std::string text = getPlantStructureXML(arch, plantIDs, options);
    io::AtomicFile file(filename);
    file.write(text);
    file.commit();
}

std::string getObjectTableJSON(const PlantArchitecture& arch, const std::vector<unsigned>& plantIDs,
                               const ObjectTableOptions& options) {
    std::vector<const PlantInstance*> plants;
    for (unsigned id : plantIDs) plants.push_back(&arch.plant(id));
    return io::objectTableJSON(const_cast<PlantArchitecture&>(arch).context(), plants,
                               options.includeHidden);
}

std::string getObjectTableJSON(const Context& context, const ObjectTableOptions& options) {
    return io::objectTableJSON(context, {}, options.includeHidden);
}

void writeObjectTableJSON(const PlantArchitecture& arch, const std::vector<unsigned>& plantIDs,
                          const std::string& filename, const ObjectTableOptions& options) {
    const std::string text = getObjectTableJSON(arch, plantIDs, options);
    io::AtomicFile file(filename);
    file.write(text);
    file.commit();
}

void writeObjectTableJSON(const Context& context, const std::string& filename,
                          const ObjectTableOptions& options) {
    const std::string text = getObjectTableJSON(context, options);
    io::AtomicFile file(filename);
    file.write(text);
    file.commit();
}

}  // namespace plantarch
