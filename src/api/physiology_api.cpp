// PlantArchitecture: the carbohydrate and nitrogen models of its plants (docs/physiology.md).
// The budgets themselves live in physiology/budget.cpp; this file measures the plants for
// them, applies what they decide (pruning, abortion) and keeps their records.

#include <algorithm>
#include <cmath>
#include <string>

#include "api/facade_impl.h"
#include "geometry/tessellate.h"
#include "physiology/budget.h"
#include "plantarch/Error.h"

namespace plantarch {

namespace {

// Every live leaf of the plant with its drawn area (0 for one not drawn yet).
std::vector<physiology::LeafMeasure> measureLeaves(const Context& ctx, PlantInstance& plant) {
    std::vector<physiology::LeafMeasure> leaves;
    for (Shoot& s : plant.shoots) {
        if (s.removed) continue;
        for (Phytomer& ph : s.phytomers)
            for (Petiole& pt : ph.petioles)
                for (LeafOrgan& l : pt.leaves) {
                    if (l.removed) continue;
                    double area = 0.0;
                    for (ObjectID o : l.objects)
                        if (ctx.doesObjectExist(o)) area += ctx.objectArea(o);
                    leaves.push_back({&l, area});
                }
    }
    return leaves;
}

// The plant's fruit surface now (m², of the drawn fruit objects).
double fruitArea(const Context& ctx, const PlantInstance& plant) {
    double area = 0.0;
    auto add = [&](const FloralBud& fb) {
        if (fb.stage != FloralStage::Fruit) return;
        for (const FlowerOrgan& fl : fb.flowers)
            for (ObjectID o : fl.objects)
                if (ctx.doesObjectExist(o)) area += ctx.objectArea(o);
    };
    for (const Shoot& s : plant.shoots) {
        if (s.removed) continue;
        for (const Phytomer& ph : s.phytomers)
            for (const Petiole& pt : ph.petioles)
                for (const FloralBud& fb : pt.floralBuds) add(fb);
        for (const FloralBud& fb : s.terminalFloralBuds) add(fb);
    }
    return area;
}

// The volume a drawn organ's surface encloses, m³ (for a surface that is not quite closed,
// the cones from its centre to its triangles, about the same).
double enclosedVolume(const Context& ctx, ObjectID id) {
    if (!ctx.doesObjectExist(id)) return 0.0;
    const PrimitiveRange range = ctx.objectPrimitives(id);
    if (range.count == 0) return 0.0;
    glm::dvec3 centre(0.0);
    for (PrimitiveID p = range.first; p < range.end(); ++p)
        for (const vec3& v : ctx.primitiveVertices(p)) centre += glm::dvec3(v);
    centre /= 3.0 * double(range.count);
    double six = 0.0;
    for (PrimitiveID p = range.first; p < range.end(); ++p) {
        const auto v = ctx.primitiveVertices(p);
        const glm::dvec3 a = glm::dvec3(v[0]) - centre, b = glm::dvec3(v[1]) - centre,
                         c = glm::dvec3(v[2]) - centre;
        six += glm::dot(a, glm::cross(b, c));
    }
    return std::abs(six) / 6.0;
}

// What the carbon budget needs of every shoot (indexed by shoot ID); `input` per shoot.
std::vector<physiology::ShootMeasure> measureShoots(const Context& ctx, const PlantInstance& plant,
                                                    const std::map<unsigned, double>& input) {
    const CarbohydrateParameters& p = plant.phenology.carbohydrates;
    std::vector<physiology::ShootMeasure> out(plant.shoots.size());
    for (const Shoot& s : plant.shoots) {
        if (s.removed) continue;
        physiology::ShootMeasure& m = out[s.id];
        auto floral = [&](const FloralBud& fb) {
            if (fb.stage == FloralStage::FlowerClosed || fb.stage == FloralStage::FlowerOpen ||
                fb.stage == FloralStage::Fruit)
                m.flowers += unsigned(fb.flowers.size());
            if (fb.stage == FloralStage::Fruit)
                for (const FlowerOrgan& fl : fb.flowers)
                    for (ObjectID o : fl.objects) m.fruitVolume += enclosedVolume(ctx, o);
        };
        for (const Phytomer& ph : s.phytomers) {
            const double r = ph.internode.radius;
            const double volume = M_PI * r * r * double(ph.internode.length) * ph.internodeFraction;
            m.woodVolume += volume;
            m.woodCarbon += physiology::woodCarbon(p, volume);
            for (const Petiole& pt : ph.petioles) {
                for (const LeafOrgan& l : pt.leaves)
                    if (!l.removed)
                        for (ObjectID o : l.objects)
                            if (ctx.doesObjectExist(o)) m.leafArea += ctx.objectArea(o);
                for (const FloralBud& fb : pt.floralBuds) floral(fb);
            }
        }
        for (const FloralBud& fb : s.terminalFloralBuds) floral(fb);
        if (auto it = input.find(s.id); it != input.end()) m.input = it->second;
    }
    return out;
}

bool carbonStarted(const PlantInstance& plant) {
    for (const Shoot& s : plant.shoots)
        if (!s.removed && s.carbon) return true;
    return false;
}

}  // namespace

void PlantArchitecture::startPhysiology(unsigned plantID) {
    PlantInstance& plant = impl_->store.plant(plantID);
    impl_->physiology[plantID];  // the plant's records start now
    if (plant.phenology.carbohydrates.enabled && !carbonStarted(plant))
        physiology::startCarbon(plant, measureShoots(*context_, plant, {}));
    if (plant.phenology.nitrogen.enabled && !plant.nitrogen)
        physiology::startNitrogen(plant, measureLeaves(*context_, plant));
}

void PlantArchitecture::stepPhysiology(unsigned plantID, double days) {
    PlantInstance& plant = impl_->store.plant(plantID);
    Impl::PlantPhysiology& state = impl_->physiology[plantID];
    PhysiologyRecord record;
    record.plant = plantID;
    record.age = plant.age;
    record.days = days;
    record.temperature = impl_->airTemperature;
    record.absorbedPar = state.absorbed;
    const std::vector<physiology::LeafMeasure> leaves = measureLeaves(*context_, plant);
    for (const auto& leaf : leaves) record.leafArea += leaf.area;
    state.absorbed = 0.0;
    if (plant.nitrogen)
        physiology::stepNitrogen(plant, leaves, fruitArea(*context_, plant), days, record);
    if (carbonStarted(plant)) {
        const physiology::CarbonActions actions =
            physiology::stepCarbon(plant, measureShoots(*context_, plant, state.input),
                                   impl_->airTemperature, days, record);
        state.input.clear();
        for (const physiology::AbortedBud& a : actions.aborted) {
            Shoot& s = plant.shoots[a.shoot];
            FloralBud& fb = a.terminal
                                ? s.terminalFloralBuds[a.index]
                                : s.phytomers[a.node].petioles[a.petiole].floralBuds[a.index];
            for (FlowerOrgan& fl : fb.flowers) {
                for (ObjectID o : fl.objects)
                    if (context_->doesObjectExist(o)) context_->deleteObject(o);
                fl.objects.clear();
            }
        }
        // The dying shoots, from the base up, so a shoot already gone with its parent is left.
        for (unsigned id : actions.prune)
            if (!plant.shoots[id].removed) pruneBranch(plantID, id, 0);
        if (!actions.aborted.empty()) updateGeometry(plantID);
    }
    state.records.push_back(record);
}

void PlantArchitecture::enableCarbohydrateModel(unsigned plantID) {
    PlantInstance& plant = impl_->store.plant(plantID);
    plant.phenology.carbohydrates.enabled = true;
    startPhysiology(plantID);
}

void PlantArchitecture::enableNitrogenModel(unsigned plantID) {
    PlantInstance& plant = impl_->store.plant(plantID);
    plant.phenology.nitrogen.enabled = true;
    startPhysiology(plantID);
}

bool PlantArchitecture::hasCarbohydrateModel(unsigned plantID) const {
    return carbonStarted(impl_->store.plant(plantID));
}

bool PlantArchitecture::hasNitrogenModel(unsigned plantID) const {
    return impl_->store.plant(plantID).nitrogen.has_value();
}

void PlantArchitecture::addPlantNitrogen(unsigned plantID, double grams) {
    PlantInstance& plant = impl_->store.plant(plantID);
    if (!(grams > 0.0) || !std::isfinite(grams))
        throw Error("nitrogen added must be a finite number of grams > 0",
                    {.parameter = "grams", .value = std::to_string(grams), .validRange = "> 0"});
    if (!plant.nitrogen)
        throw Error("plant " + std::to_string(plantID) +
                    " has no nitrogen model: enable it before fertilising");
    physiology::addNitrogen(plant, grams);
}

void PlantArchitecture::addLeafPhotosynthesis(const std::map<ObjectID, double>& netRates,
                                              double hours) {
    if (!(hours >= 0.0) || hours > 24.0)
        throw Error(
            "hours must be from 0 to 24",
            {.parameter = "hours", .value = std::to_string(hours), .validRange = "0 to 24"});
    for (const auto& [leaf, rate] : netRates)
        if (!std::isfinite(rate) || std::abs(rate) > 1000.0)
            throw Error("net photosynthesis of object " + std::to_string(leaf) +
                            " must be a finite rate within +-1000 umol m-2 s-1",
                        {.parameter = "netRates",
                         .value = std::to_string(rate),
                         .validRange = "-1000 to 1000"});
    struct Owner {
        unsigned plant, shoot;
    };
    std::map<ObjectID, Owner> owners;
    for (unsigned id : getAllPlantIDs())
        for (const Shoot& s : impl_->store.plant(id).shoots) {
            if (s.removed) continue;
            for (const Phytomer& ph : s.phytomers)
                for (const Petiole& pt : ph.petioles)
                    for (const LeafOrgan& l : pt.leaves)
                        for (ObjectID o : l.objects) owners[o] = {id, s.id};
        }
    // Checked whole before anything is added.
    for (const auto& [leaf, rate] : netRates) {
        auto it = owners.find(leaf);
        if (it == owners.end())
            throw Error("object " + std::to_string(leaf) + " is not a leaf of any plant");
        if (!carbonStarted(impl_->store.plant(it->second.plant)))
            throw Error("plant " + std::to_string(it->second.plant) +
                        " has no carbohydrate budget: enable it first");
    }
    for (const auto& [leaf, rate] : netRates) {
        const Owner& o = owners.at(leaf);
        impl_->physiology[o.plant].input[o.shoot] +=
            rate * context_->objectArea(leaf) * hours * 3600.0 * 1e-6;
    }
}

void PlantArchitecture::setAirTemperature(double celsius) {
    if (!(celsius >= -50.0 && celsius <= 60.0))
        throw Error(
            "air temperature must be from -50 to 60 degrees C",
            {.parameter = "celsius", .value = std::to_string(celsius), .validRange = "-50 to 60"});
    impl_->airTemperature = celsius;
}

void PlantArchitecture::addAbsorbedLight(unsigned plantID, double molPhotons) {
    impl_->store.plant(plantID);
    if (!(molPhotons >= 0.0) || !std::isfinite(molPhotons))
        throw Error("absorbed light must be a finite amount >= 0",
                    {.parameter = "molPhotons", .value = std::to_string(molPhotons)});
    impl_->physiology[plantID].absorbed += molPhotons;
}

const std::vector<PhysiologyRecord>& PlantArchitecture::getPhysiologyRecords(
    unsigned plantID) const {
    impl_->store.plant(plantID);
    static const std::vector<PhysiologyRecord> none;
    auto it = impl_->physiology.find(plantID);
    return it == impl_->physiology.end() ? none : it->second.records;
}

}  // namespace plantarch
