#pragma once
// The collision state of one PlantArchitecture, and what each thread grows plants with when
// collision avoidance is on.

#include <map>
#include <memory>

#include "geometry/prototype_cache.h"
#include "model/function_registry.h"
#include "model/plant_store.h"

namespace plantarch::collision {

class World;
class AttractionIndex;
class ProxyCache;

struct CollisionState {
    /// The scene (null until a collision feature is enabled; shared with canopy workers).
    std::shared_ptr<World> world;
    /// Spatial indexes of the plants' own attraction points: a cache (the points are
    /// PlantInstance::attraction), an index is rebuilt when they differ from its own.
    std::map<unsigned, std::shared_ptr<const AttractionIndex>> attractionIndexes;
    /// Collision shapes of the cached prototypes, by prototype address (dropped with them).
    std::shared_ptr<ProxyCache> proxies;
};

/// The scene of `state`, made on first use.
World& worldOf(CollisionState& state);
/// The proxy shapes of `state`, made on first use.
ProxyCache& proxyCache(CollisionState& state);

/// The attraction points a plant steers by: its own (PlantInstance::attraction, indexed on
/// first use and again whenever they change), else the global ones, else null. The pointer
/// stays valid until the next call for this plant.
const AttractionIndex* attractionFor(CollisionState& state, const PlantInstance& plant);

/// Whether any collision feature is on (for any plant of `store`).
bool collisionActive(const CollisionState& state, const PlantStore& store);

/// What one thread grows, refreshes and clears plants with: the shoot types and functions
/// (shared, read only) and caches of its own.
struct Worker {
    const PlantStore& store;
    const FunctionRegistry& functions;
    PrototypeCache& prototypes;
    ProxyCache& proxies;
};

/// The caches of a helper thread: the prototypes built so far (shared, immutable), memos and
/// proxy shapes of its own.
class WorkerCaches {
public:
    explicit WorkerCaches(const PrototypeCache& shared);
    ~WorkerCaches();
    WorkerCaches(const WorkerCaches&) = delete;
    WorkerCaches& operator=(const WorkerCaches&) = delete;

    /// A worker growing plants of `store` with these caches.
    Worker worker(const PlantStore& store) {
        return {store, prototypes_.functions(), prototypes_, *proxies_};
    }

private:
    PrototypeCache prototypes_;
    std::unique_ptr<ProxyCache> proxies_;
};

}  // namespace plantarch::collision
