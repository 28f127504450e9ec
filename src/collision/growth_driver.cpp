// Growing plants with collision avoidance.
//
// Without soft avoidance each plant only perceives static things (solid obstacles, attraction
// points), so plants grow independently, in parallel. With soft avoidance plants perceive
// each other's organs, so they grow together in steps that end on the whole multiples of the
// update interval of the collision clock; after each step the scene is refreshed from every
// plant's state. Within a step every plant sees the scene as it stood at the step's start, so
// the order (and thread) in which plants are grown changes nothing: the same seed gives the
// same plants for any thread count. Cone rays come from per-organ streams (steering.cpp).

#include "collision/growth_driver.h"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>

#include "collision/attraction.h"
#include "collision/clearance.h"
#include "collision/collision_world.h"
#include "collision/proxies.h"
#include "collision/steering.h"
#include "core/parallel.h"
#include "geometry/tessellate.h"
#include "growth/growth.h"

namespace plantarch::collision {

namespace {

// Threads that forEach runs n tasks on.
int threadsFor(std::size_t n, const std::vector<Worker>& workers) {
    return std::max(1, std::min(int(workers.size()), int(n)));
}

// Runs f(index, worker) for every index, on up to workers.size() threads (one worker each);
// rethrows the error of the lowest index once all have run. Index i always runs on thread
// i % threads (the canopy builds plant i there too): a plant's memory is then allocated and
// freed by one thread. Plants handed to whichever thread was free made threads free each
// other's memory as shoots grew, and wait for the allocator's lock of the other thread's
// arena: some 700 sleeps per canopy and a fifth of the soft canopy's time.
template <class F>
void forEach(std::size_t n, const std::vector<Worker>& workers, F&& f) {
    ParallelErrors errors;
    const int threads = threadsFor(n, workers);
#pragma omp parallel for schedule(static, 1) \
    num_threads(threads) if (threads > 1 && !omp_in_parallel())
    for (int i = 0; i < int(n); ++i)
        errors.run(i, [&] { f(std::size_t(i), workers[std::size_t(omp_get_thread_num())]); });
    errors.rethrow();
}

// Grows one plant steered by the scene and its attraction points; growth ends by turning its
// side organs out of the solid obstacles and the ground.
void growOne(const World& world, GrowthSlot& slot, const Worker& w, double days,
             std::uint64_t seed) {
    SceneSteering steering(&world, slot.attraction, seed);
    SolidClearance solid(w, world);
    OrganObstacle* const solids[] = {&solid};
    ClearanceCounts counts;
    GrowthContext growth{w.store, w.functions, w.prototypes, &steering};
    if (solid.active()) growth.obstacles = solids;
    growth.clearanceCounts = &counts;
    growPlant(growth, *slot.plant, days, slot.deletes);
    countClearance(world, counts);
}

// Makes a plant's proxies for the next install into its memo, with their spheres and grid
// cells, and notes whether they changed. Touches nothing the scene's queries read, so it runs
// on the thread that grew the plant, while other plants still grow (their state is at hand).
void prepare(const World& world, const CollisionOrgans& organs, PlantInstance& plant,
             const Worker& w) {
    PlantProxyMemo& memo = *world.memos.at(plant.id);
    PlantProxies& next = memo.next;
    memo.epoch = world.calls;
    // Changes are told from the memo's last proxies: if those never reached the scene (another
    // plant's growth failed before the install), these must.
    memo.nextChanged =
        buildProxies(w, plant, organs, memo, next.triangles, next.tags) || memo.pending;
    memo.pending = true;
    if (memo.nextChanged) world.index(next);
}

// Thread time spent preparing proxies during one growth step.
struct PrepareClock {
    std::atomic<std::int64_t> nanoseconds{0};
    template <class F>
    void time(F&& f) {
        const auto start = std::chrono::steady_clock::now();
        f();
        nanoseconds.fetch_add(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                  std::chrono::steady_clock::now() - start)
                                  .count(),
                              std::memory_order_relaxed);
    }
};

// Makes the prepared proxies of these plants the scene's and rebuilds its grid. `prepared`:
// the seconds the preparation took (thread time over the number of threads).
void install(World& world, std::vector<GrowthSlot>& slots, const std::vector<std::size_t>& which,
             double prepared, int threads) {
    const auto start = std::chrono::steady_clock::now();
    for (std::size_t i : which) {
        const unsigned id = slots[i].plant->id;
        PlantProxyMemo& memo = *world.memos.at(id);
        world.swapPlantProxies(id, memo.next, memo.nextChanged);
        memo.pending = false;
        world.stale.erase(id);
    }
    world.commit(threads);
    AtomicStats& st = world.stats();
    st.sceneRefreshes.fetch_add(1, std::memory_order_relaxed);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    st.refreshSeconds.store(st.refreshSeconds.load() + prepared + seconds);
}

void reserve(World& world, std::vector<GrowthSlot>& slots, const std::vector<std::size_t>& which) {
    std::vector<unsigned> ids;
    for (std::size_t i : which) ids.push_back(slots[i].plant->id);
    world.reservePlants(ids);
}

void refresh(World& world, std::vector<GrowthSlot>& slots, const std::vector<std::size_t>& which,
             const std::vector<Worker>& workers) {
    if (!world.soft() || which.empty()) return;
    const auto start = std::chrono::steady_clock::now();
    reserve(world, slots, which);
    const CollisionOrgans organs = world.soft()->obstacles;
    forEach(which.size(), workers, [&](std::size_t k, const Worker& w) {
        prepare(world, organs, *slots[which[k]].plant, w);
    });
    install(world, slots, which,
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
            threadsFor(which.size(), workers));
}

}  // namespace

void refreshPlants(World& world, std::vector<GrowthSlot>& slots,
                   const std::vector<Worker>& workers) {
    ++world.calls;
    std::vector<std::size_t> all(slots.size());
    for (std::size_t i = 0; i < slots.size(); ++i) all[i] = i;
    refresh(world, slots, all, workers);
}

void growTogether(World& world, std::vector<GrowthSlot>& slots, double days, std::uint64_t seed,
                  const std::vector<Worker>& workers, const ProgressCallback& progress) {
    if (!world.soft()) {
        forEach(slots.size(), workers,
                [&](std::size_t i, const Worker& w) { growOne(world, slots[i], w, days, seed); });
        if (progress) progress("growing", 1.0);
        return;
    }
    // Memos of prototype keys and areas last for the whole call (shoot types cannot change).
    struct Pin {
        const std::vector<Worker>& workers;
        explicit Pin(const std::vector<Worker>& w) : workers(w) {
            for (const Worker& worker : workers) {
                worker.prototypes.clearCallMemos();
                worker.prototypes.memosPinned = true;
            }
        }
        ~Pin() {
            for (const Worker& worker : workers) worker.prototypes.memosPinned = false;
        }
    } pin(workers);
    ++world.calls;
    // Plants new to the scene, or edited since it was refreshed, are seen from now on.
    std::vector<std::size_t> fresh, all;
    for (std::size_t i = 0; i < slots.size(); ++i) {
        all.push_back(i);
        const unsigned id = slots[i].plant->id;
        if (!world.hasPlant(id) || world.stale.count(id)) fresh.push_back(i);
    }
    refresh(world, slots, fresh, workers);
    reserve(world, slots, all);
    const CollisionOrgans organs = world.soft()->obstacles;

    const double interval = world.soft()->updateInterval;
    double done = 0.0;
    while (days - done > 1e-9) {
        const double clock = world.clock;
        const double next = (std::floor(clock / interval + 1e-9) + 1.0) * interval;
        const bool reaches = days - done >= next - clock - 1e-9;
        const double step = reaches ? next - clock : days - done;
        // A step that ends on the interval refreshes the scene: each plant's proxies are
        // prepared by the thread that grew it, right after (the scene itself is left as it
        // stood for the plants still growing), and installed once all have grown.
        PrepareClock prepareClock;
        forEach(slots.size(), workers, [&](std::size_t i, const Worker& w) {
            growOne(world, slots[i], w, step, seed);
            if (reaches) prepareClock.time([&] { prepare(world, organs, *slots[i].plant, w); });
        });
        world.clock = reaches ? next : clock + step;
        done += step;
        if (reaches)
            install(world, slots, all,
                    double(prepareClock.nanoseconds.load()) * 1e-9 /
                        double(threadsFor(slots.size(), workers)),
                    threadsFor(slots.size(), workers));
        if (progress) progress("growing", std::min(1.0, done / days));
    }
}

WorkerCaches::WorkerCaches(const PrototypeCache& shared)
    : prototypes_(shared.share()), proxies_(std::make_unique<ProxyCache>()) {}

WorkerCaches::~WorkerCaches() = default;

const AttractionIndex* attractionFor(CollisionState& state, const PlantInstance& plant) {
    if (!plant.attraction) {
        state.attractionIndexes.erase(plant.id);
        return state.world ? state.world->globalAttraction.get() : nullptr;
    }
    // The index is derived from the plant's points: rebuilt when they changed.
    std::shared_ptr<const AttractionIndex>& index = state.attractionIndexes[plant.id];
    if (!index || index->options() != *plant.attraction)
        index = std::make_shared<const AttractionIndex>(*plant.attraction);
    return index.get();
}

bool collisionActive(const CollisionState& state, const PlantStore& store) {
    for (const auto& [id, plant] : store.plants)
        if (plant.attraction) return true;
    const World* w = state.world.get();
    return w && (w->soft() || w->solid() || w->globalAttraction);
}

World& worldOf(CollisionState& state) {
    if (!state.world) state.world = std::make_shared<World>();
    return *state.world;
}

void advanceWithCollision(CollisionState& state, PlantStore& store, const Worker& main,
                          Context& ctx, const GrowthRequest& request) {
    World& world = worldOf(state);
    std::vector<GrowthSlot> slots;
    for (unsigned id : request.plantIDs) {
        PlantInstance& plant = store.plant(id);
        slots.push_back({&plant, attractionFor(state, plant), {}});
    }
    // Helpers for the other threads when plants grow together (they share nothing mutable).
    std::vector<std::unique_ptr<WorkerCaches>> helpers;
    std::vector<Worker> workers{main};
    const int threads = omp_in_parallel() ? 1 : omp_get_max_threads();
    for (int t = 1; t < std::min(threads, int(slots.size())); ++t) {
        helpers.push_back(std::make_unique<WorkerCaches>(main.prototypes));
        workers.push_back(helpers.back()->worker(store));
    }
    growTogether(world, slots, request.days, request.seed, workers, request.progress);
    for (GrowthSlot& slot : slots) {
        for (ObjectID o : slot.deletes)
            if (ctx.doesObjectExist(o)) ctx.deleteObject(o);
        tessellatePlant(store, main.prototypes, ctx, *slot.plant);
    }
}

}  // namespace plantarch::collision
