#pragma once
// Growing plants while they perceive each other (see growth_driver.cpp).

#include <cstdint>
#include <vector>

#include "collision/collision_state.h"
#include "plantarch/Progress.h"

namespace plantarch::collision {

/// One plant to grow: its state, its attraction points (its own or the global ones, may be
/// null) and, after growth, the object IDs of organs that fell off.
struct GrowthSlot {
    PlantInstance* plant = nullptr;
    const AttractionIndex* attraction = nullptr;
    std::vector<ObjectID> deletes;
};

/// Grows the plants by `days` with collision avoidance. Thread t grows with workers[t] (its
/// caches); with soft avoidance the plants advance together, the collision scene refreshed
/// at every whole update interval of the world's clock. Results do not depend on the number
/// of threads. Errors from growth are rethrown after all threads stop.
void growTogether(World& world, std::vector<GrowthSlot>& slots, double days, std::uint64_t seed,
                  const std::vector<Worker>& workers, const ProgressCallback& progress = {});

/// Rebuilds the collision proxies of these plants now (single plant edits, new plants).
void refreshPlants(World& world, std::vector<GrowthSlot>& slots,
                   const std::vector<Worker>& workers);

/// One advanceTime call: the plants, the days, the scene seed, progress (may be empty).
struct GrowthRequest {
    const std::vector<unsigned>& plantIDs;
    double days;
    std::uint64_t seed;
    const ProgressCallback& progress;
};

/// advanceTime with collision avoidance on: grows the plants of `store` (on several threads
/// when soft avoidance makes them grow together; `main` is the calling thread's worker),
/// deletes fallen organs from `ctx` and regenerates the plants' geometry.
void advanceWithCollision(CollisionState& state, PlantStore& store, const Worker& main,
                          Context& ctx, const GrowthRequest& request);

}  // namespace plantarch::collision
