// PlantArchitecture: growth over time, phenology, progress and the phytomer functions.

#include <algorithm>
#include <cmath>
#include <exception>
#include <functional>
#include <optional>
#include <string>

#include "api/facade_impl.h"
#include "collision/clearance.h"
#include "collision/growth_driver.h"
#include "core/progress_steps.h"
#include "growth/growth.h"
#include "growth/organ_clearance.h"
#include "plantarch/Error.h"

namespace plantarch {

void PlantArchitecture::advanceTime(double days) {
    advanceTime(getAllPlantIDs(), days);
}

void PlantArchitecture::advanceTime(unsigned plantID, double days) {
    advanceTime(std::vector<unsigned>{plantID}, days);
}

void PlantArchitecture::advanceTime(const std::vector<unsigned>& plantIDs, double days) {
    if (!(days >= 0.0) || !std::isfinite(days))
        throw Error("time step must be a finite number of days >= 0",
                    {.parameter = "days", .value = std::to_string(days), .validRange = ">= 0"});
    for (unsigned id : plantIDs) impl_->store.plant(id);  // all exist, or nothing happens
    std::vector<unsigned> budgeted;
    for (unsigned id : plantIDs)
        if (hasCarbohydrateModel(id) || hasNitrogenModel(id)) budgeted.push_back(id);
    if (budgeted.empty()) {
        growPlants(plantIDs, days);
        return;
    }
    // Plants with budgets grow in steps of at most a day (all plants together, so they grow
    // as one scene), each step followed by their budgets.
    double done = 0.0;
    while (done < days) {
        const double step = std::min(1.0, days - done);
        growPlants(plantIDs, step);
        for (unsigned id : budgeted) stepPhysiology(id, step);
        done += step;
    }
}

void PlantArchitecture::growPlants(const std::vector<unsigned>& plantIDs, double days) {
    impl_->store.triangleLimit = context_->triangleLimit();  // growth stops past it
    if (collision::collisionActive(impl_->collision, impl_->store)) {
        collision::advanceWithCollision(impl_->collision, impl_->store, impl_->worker(), *context_,
                                        {plantIDs, days, seed_, impl_->progress});
        return;
    }
    // Progress within a plant too (a tree over years takes seconds), counting its growth as
    // 0.9 of it and its geometry as the rest. A callback that throws stops the job once the
    // plant it interrupted is whole again.
    ProgressSteps steps(impl_->progress, "growing", double(plantIDs.size()));
    std::exception_ptr stopped;
    std::size_t done = 0;
    const std::function<void(double)> onDay = [&](double fraction) {
        if (stopped) return;
        try {
            steps.at(double(done) + 0.9 * fraction);
        } catch (...) {
            stopped = std::current_exception();
        }
    };
    for (unsigned id : plantIDs) {
        std::vector<ObjectID> deletes;
        growPlant(impl_->growth(), impl_->store.plant(id), days, deletes,
                  steps.active() ? onDay : std::function<void(double)>());
        for (ObjectID o : deletes)
            if (context_->doesObjectExist(o)) context_->deleteObject(o);
        updateGeometry(id);
        if (stopped) std::rethrow_exception(stopped);
        steps.at(double(++done));
    }
    steps.finish();
}

void PlantArchitecture::setGroundClearance(bool on) {
    impl_->store.groundClearance = on;
    for (unsigned id : getAllPlantIDs()) setGroundClearance(id, on);
}

bool PlantArchitecture::getGroundClearance() const {
    return impl_->store.groundClearance;
}

void PlantArchitecture::setGroundClearance(unsigned plantID, bool on) {
    PlantInstance& p = impl_->store.plant(plantID);
    if (p.groundClearance == on) return;
    p.groundClearance = on;
    // The turns follow the setting now, as they would at the end of a growth step.
    if (impl_->collision.world)
        collision::clearOrgans(impl_->worker(), *impl_->collision.world, p);
    else
        clearSideOrgans(impl_->store, impl_->prototypes, p);
    updateGeometry(plantID);
}

bool PlantArchitecture::getGroundClearance(unsigned plantID) const {
    return impl_->store.plant(plantID).groundClearance;
}

void PlantArchitecture::enableGroundClipping(float height) {
    if (!std::isfinite(height))
        throw Error(
            "ground clipping height must be finite",
            {.parameter = "height", .value = std::to_string(height), .validRange = "finite, m"});
    impl_->store.groundClipping = height;
    for (auto& [id, p] : impl_->store.plants)
        if (clipBelowGround(impl_->store, impl_->prototypes, p, height)) updateGeometry(id);
}

void PlantArchitecture::disableGroundClipping() {
    impl_->store.groundClipping.reset();
}

std::optional<float> PlantArchitecture::getGroundClipping() const {
    return impl_->store.groundClipping;
}

void PlantArchitecture::enableEpicormicChildShoots(unsigned plantID, const std::string& shootType,
                                                   float perMetrePerDay) {
    PlantInstance& p = impl_->store.plant(plantID);
    if (!(perMetrePerDay >= 0.0f) || !std::isfinite(perMetrePerDay))
        throw Error("invalid water sprout probability",
                    {.parameter = "probability",
                     .value = std::to_string(perMetrePerDay),
                     .validRange = ">= 0, per m of shoot per day"});
    if (perMetrePerDay == 0.0f) {
        p.epicormic.reset();
        return;
    }
    impl_->store.shootTypeFor(p, shootType);  // an unknown type names the known ones
    p.epicormic = EpicormicShoots{shootType, perMetrePerDay};
}

void PlantArchitecture::makePlantDormant(unsigned plantID) {
    PlantInstance& p = impl_->store.plant(plantID);
    changeSeason(impl_->growth(), p, false);
    updateGeometry(plantID);
}

void PlantArchitecture::breakPlantDormancy(unsigned plantID) {
    PlantInstance& p = impl_->store.plant(plantID);
    changeSeason(impl_->growth(), p, true);
    updateGeometry(plantID);
}

bool PlantArchitecture::isPlantDormant(unsigned plantID) const {
    return impl_->store.plant(plantID).stage == PhenologyStage::Dormant;
}

void PlantArchitecture::setProgressCallback(ProgressCallback callback) {
    impl_->progress = std::move(callback);
}

void PlantArchitecture::setPlantPhenologicalThresholds(unsigned plantID,
                                                       const PhenologyParameters& t) {
    validate(t, "phenology");
    PlantInstance& p = impl_->store.plant(plantID);
    p.phenology = t;
    if (p.dormancyBreakTime < 0.0)
        p.nextDormancyBreak =
            t.time_to_dormancy_break < 0.0f ? -1.0 : p.age + t.time_to_dormancy_break;
    else
        p.senescenceTime =
            t.time_to_senescence < 0.0f ? -1.0 : p.dormancyBreakTime + t.time_to_senescence;
}

void PlantArchitecture::setDefaultPhenology(const PhenologyParameters& t) {
    validate(t, "phenology");
    impl_->store.defaultPhenology = t;
}

PhenologyParameters PlantArchitecture::getDefaultPhenology() const {
    return impl_->store.defaultPhenology;
}

PhenologyStage PlantArchitecture::getPhenologyStage(unsigned plantID) const {
    return impl_->store.plant(plantID).stage;
}

void PlantArchitecture::registerPhytomerCreationFunction(const std::string& name,
                                                         PhytomerCreationFunction fn) {
    if (name.empty() || !fn)
        throw Error("a phytomer creation function needs a name and a function",
                    {.parameter = "name", .value = name});
    impl_->functions.creationFunctions[name] = std::move(fn);
}

void PlantArchitecture::registerPhytomerCallbackFunction(const std::string& name,
                                                         PhytomerCallbackFunction fn) {
    if (name.empty() || !fn)
        throw Error("a phytomer callback function needs a name and a function",
                    {.parameter = "name", .value = name});
    impl_->functions.callbackFunctions[name] = std::move(fn);
}

}  // namespace plantarch
