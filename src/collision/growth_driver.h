#pragma once
// Growing plants while they perceive each other (see growth_driver.cpp).

#include <cstdint>
#include <memory>
#include <vector>

#include "model/architecture_impl.h"

namespace plantarch::collision {

class World;
class AttractionIndex;

/// One plant to grow: its state, its attraction points (its own or the global ones, may be
/// null) and, after growth, the object IDs of organs that fell off.
struct GrowthSlot {
    PlantInstance* plant = nullptr;
    const AttractionIndex* attraction = nullptr;
    std::vector<ObjectID> deletes;
};

/// Grows the plants by `days` with collision avoidance. Thread t grows with threadImpls[t]
/// (its prototype caches); with soft avoidance the plants advance together, the collision
/// scene refreshed at every whole update interval of the world's clock. Results do not
/// depend on the number of threads. Errors from growth are rethrown after all threads stop.
void growTogether(World& world, std::vector<GrowthSlot>& slots, double days, std::uint64_t seed,
                  const std::vector<PlantArchitecture::Impl*>& threadImpls,
                  const ProgressCallback& progress = {});

/// Rebuilds the collision proxies of these plants now (single plant edits, new plants).
void refreshPlants(World& world, std::vector<GrowthSlot>& slots,
                   const std::vector<PlantArchitecture::Impl*>& threadImpls);

/// A worker copy of `impl` for growing on another thread: same shoot types, species,
/// functions and prototypes (shared, immutable), its own caches; no plants.
std::unique_ptr<PlantArchitecture::Impl> workerImpl(const PlantArchitecture::Impl& impl);

/// The attraction points a plant steers by: its own (PlantInstance::attraction, indexed on
/// first use and again whenever they change), else the global ones, else null. The pointer
/// stays valid until the next call for this plant.
const AttractionIndex* attractionFor(PlantArchitecture::Impl& impl, unsigned plantID);

/// Whether any collision feature is on.
bool collisionActive(const PlantArchitecture::Impl& impl);

/// advanceTime with collision avoidance on: grows the plants (on several threads when soft
/// avoidance makes them grow together), deletes fallen organs and regenerates the geometry.
void advanceWithCollision(PlantArchitecture::Impl& impl, Context& ctx, std::uint64_t seed,
                          const std::vector<unsigned>& plantIDs, double days);

/// The collision world of `impl`, made on first use.
World& worldOf(PlantArchitecture::Impl& impl);

}  // namespace plantarch::collision
