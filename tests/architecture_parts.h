#pragma once
// The internal parts of a PlantArchitecture (plant store, function registry, prototype cache,
// collision state) put together the way the facade puts them, for tests that read and change
// plants and the collision scene directly.

#include <map>
#include <string>
#include <vector>

#include "collision/collision_state.h"
#include "collision/collision_world.h"
#include "collision/growth_driver.h"
#include "growth/growth.h"
#include "plantarch/LeafShapes.h"
#include "plantarch/PlantArchitecture.h"

namespace plantarch::testing {

// The parts of a PlantArchitecture around copies of some of its plants and its shoot types.
// The registry holds the procedural leaf prototype (built with the public LeafShapes API,
// as a user's function would be), a one-triangle flower and fruit, and no phytomer
// functions: the copies' shoot types name none.
struct Parts {
    PlantStore store;
    FunctionRegistry functions;
    PrototypeCache prototypes{functions};
    collision::CollisionState collision;
    std::uint64_t seed;

    Parts(const PlantArchitecture& arch, const std::vector<unsigned>& ids) : seed(arch.seed()) {
        functions.leafPrototypes["procedural"] = [](const LeafPrototype& p, Rng& rng, int leaflet) {
            return OrganPrototype{{buildLeafPrototype(p, rng, leaflet),
                                   Material{p.color, leafTextureFile(p, leaflet), "leaf"}}};
        };
        // Flowers and fruit: one triangle each, under the name a shoot type without a
        // prototype function of its own falls back to.
        for (const char* name : {"builtin_flower", "builtin_fruit"})
            functions.floralPrototypes[name] = [](const FloralPrototypeRequest& r, Rng&) {
                Mesh m;
                m.positions = {{0, 0, 0}, {1, 0, 0}, {0.5f, 0.3f, 0}};
                m.indices = {0, 1, 2};
                return OrganPrototype{{std::move(m), Material{r.color, "", "flower"}}};
            };
        auto withoutFunctions = [](std::map<std::string, ShootParameters>& types) {
            for (auto& [label, t] : types) {
                t.phytomer_parameters.phytomer_creation_function.clear();
                t.phytomer_parameters.phytomer_callback_function.clear();
                t.phytomer_parameters.inflorescence.flower_prototype_function.clear();
                t.phytomer_parameters.inflorescence.fruit_prototype_function.clear();
            }
        };
        store.shootTypes = arch.getCurrentShootParameters();
        withoutFunctions(store.shootTypes);
        for (unsigned id : ids) {
            PlantInstance copy = arch.plant(id);
            withoutFunctions(copy.shootTypes);
            store.plants.emplace(id, std::move(copy));
        }
        store.nextStream = ids.empty() ? 0 : arch.plant(ids.back()).stream + 1;
    }

    PlantInstance& plant(unsigned id) { return store.plant(id); }
    collision::Worker worker() {
        return {store, functions, prototypes, collision::proxyCache(collision)};
    }
    collision::World& world() { return collision::worldOf(collision); }

    // Soft avoidance with the default options (leaves are the obstacles).
    void enableSoftAvoidance() { world().setSoft(SoftCollisionOptions{}, emptyContext); }

    // Grows every plant by `days` with collision avoidance, on two threads as a canopy grows
    // (the second with caches of its own).
    void advance(double days) {
        std::vector<collision::GrowthSlot> slots;
        for (auto& [id, p] : store.plants) slots.push_back({&p, nullptr, {}});
        collision::WorkerCaches helper(prototypes);
        collision::growTogether(world(), slots, days, seed, {worker(), helper.worker(store)});
    }

    // Grows one plant by `days` without collision avoidance, steered by `steering` if given.
    void grow(unsigned id, double days, Steering* steering = nullptr) {
        std::vector<ObjectID> deletes;
        growPlant(GrowthContext{store, functions, prototypes, steering}, plant(id), days, deletes);
    }

    // The prototype caches dropped, as registering a prototype function does.
    void dropPrototypes() {
        prototypes.clear();
        collision.proxies.reset();
    }

    Context emptyContext;  // no obstacle objects
};

}  // namespace plantarch::testing
