#pragma once
// The state behind the PlantArchitecture facade, private to src/api/: one part per job. The
// facade's methods (the files of this folder) check their arguments, then call the layers
// below with the parts they need.

#include <memory>

#include "collision/collision_state.h"
#include "geometry/prototype_cache.h"
#include "growth/growth.h"
#include "model/function_registry.h"
#include "model/plant_store.h"
#include "plantarch/Physiology.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/Species.h"

namespace plantarch {

struct PlantArchitecture::Impl {
    PlantStore store;            ///< plants, shoot types, default phenology
    FunctionRegistry functions;  ///< named prototype and phytomer functions
    PrototypeCache prototypes{functions};
    collision::CollisionState collision;
    std::shared_ptr<const SpeciesModel> species;  ///< the loaded species, if any
    ProgressCallback progress;
    /// Set while a canopy's plants are built only to be grown together (collision
    /// avoidance): their initial geometry would be thrown away, so updateGeometry skips it.
    bool geometryDeferred = false;
    bool trellisGeometry = true;                        ///< setTrellisGeometry
    std::map<unsigned, std::vector<ObjectID>> trellis;  ///< trellis objects by plant

    /// What the physiology of a plant keeps between budget steps (physiology_api.cpp).
    struct PlantPhysiology {
        std::map<unsigned, double> input;  ///< mol C fixed per shoot since the last step
        double absorbed = 0.0;             ///< mol photons absorbed since the last step
        std::vector<PhysiologyRecord> records;
    };
    std::map<unsigned, PlantPhysiology> physiology;
    double airTemperature = 20.0;  ///< °C, for the budgets' respiration

    /// What growing by hand uses: no steering (only growth steers what it makes).
    GrowthContext growth() { return {store, functions, prototypes, nullptr}; }
    /// This thread's worker for growth with collision avoidance (steered per plant).
    collision::Worker worker() {
        return {store, functions, prototypes, collision::proxyCache(collision)};
    }

    Impl() = default;
    Impl(const Impl&) = delete;  // prototypes refers to functions
    Impl& operator=(const Impl&) = delete;
};

/// Throws if a function, OBJ file or floral family named by the shoot type is not
/// registered, missing or given bad shape parameters (plant_builder.cpp).
void checkFunctions(const FunctionRegistry& functions, const ShootParameters& params,
                    const std::string& label);

}  // namespace plantarch
