// Canopies: many plants of the loaded species, grown in parallel and merged in plant order.
//
// Each thread owns a worker (its own Context and PlantArchitecture with the same species,
// functions and seed) so nothing is shared while plants grow. A plant's numbers depend only
// on its ID (its random stream is Rng::forPlant(seed, ID)) and prototype variants are seeded
// from their parameters, so which worker grows a plant does not matter. The merge then copies
// every plant's objects into the caller's Context in plant order and object order, giving the
// same IDs and bytes whatever the thread count.

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>

#include "api/facade_impl.h"
#include "collision/collision_world.h"
#include "collision/growth_driver.h"
#include "geometry/tessellate.h"
#include "plantarch/Error.h"
#include "plantarch/SpeciesIO.h"

namespace plantarch {

namespace {

constexpr std::uint64_t kCanopyStream = 0x63616e6f7079ULL;  // scene-level draws ("canopy")

template <class F>
void forEachObjectID(PlantInstance& p, F&& f) {
    for (Shoot& s : p.shoots) {
        auto floral = [&](FloralBud& fb) {
            f(fb.peduncleObject);
            for (FlowerOrgan& fl : fb.flowers)
                for (ObjectID& id : fl.objects) f(id);
        };
        for (Phytomer& ph : s.phytomers) {
            f(ph.internode.object);
            for (Petiole& pt : ph.petioles) {
                f(pt.object);
                for (LeafOrgan& l : pt.leaves)
                    for (ObjectID& id : l.objects) f(id);
                for (FloralBud& fb : pt.floralBuds) floral(fb);
            }
        }
        for (FloralBud& fb : s.terminalFloralBuds) floral(fb);
    }
}

void checkCanopyArguments(float age, float germination) {
    if (!(age >= 0.0f) || !std::isfinite(age))
        throw Error("invalid plant age",
                    {.parameter = "age", .value = std::to_string(age), .validRange = ">= 0 days"});
    if (!(germination >= 0.0f && germination <= 1.0f))
        throw Error("germination rate out of range", {.parameter = "germination_rate",
                                                      .value = std::to_string(germination),
                                                      .validRange = "0 to 1"});
}

struct CanopyWorker {
    Context ctx;
    std::unique_ptr<PlantArchitecture> arch;
};

}  // namespace

// Copies a plant grown in another Context into this one (objects in ascending ID order, so
// IDs follow plant order) and takes over its state (its own attraction points included), with
// the object IDs remapped.
void PlantArchitecture::mergePlant(const Context& from, PlantInstance plant, Impl& owner) {
    std::vector<ObjectID> objects;
    forEachObjectID(plant, [&](ObjectID& o) {
        if (o != kNoObject) objects.push_back(o);
    });
    std::sort(objects.begin(), objects.end());
    const std::vector<std::string> labels = from.objectDataLabels();
    std::map<MaterialID, MaterialID> materials;
    std::map<ObjectID, ObjectID> remap;
    for (ObjectID o : objects) {
        const ObjectView v = from.object(o);
        auto m = materials.find(v.material);
        if (m == materials.end())
            m = materials.emplace(v.material, context_->addMaterial(from.material(v.material)))
                    .first;
        const ObjectID copy = context_->addObject(v.positions, v.uvs, v.indices, m->second);
        for (const std::string& label : labels)
            if (auto value = from.objectData(o, label))
                context_->setObjectData(copy, label, *value);
        remap[o] = copy;
    }
    forEachObjectID(plant, [&](ObjectID& o) {
        if (o != kNoObject) o = remap.at(o);
    });
    const unsigned id = plant.id;
    owner.store.plants.erase(id);
    owner.collision.attractionIndexes.erase(id);
    impl_->store.plants.emplace(id, std::move(plant));  // with its own attraction points
    impl_->collision.attractionIndexes.erase(id);
}

// With soft collision avoidance the plants must see each other while they grow, so they are
// first built (initial structure only) by the workers, then grown together by
// collision::growTogether (each step on all threads, every plant seeing the scene as it stood
// at the step's start), then tessellated by their workers and merged in plant order.
// Without it, each plant is merged into the caller's Context as soon as it is grown, in plant
// order (an ordered region), and its worker's Context emptied: the merge of one plant
// overlaps the growth of the next ones, and at most one plant per thread is held twice.
std::vector<unsigned> PlantArchitecture::buildPlantsAt(
    const std::vector<vec3>& positions, float age,
    const std::map<std::string, float>& buildParameters) {
    if (!impl_->species)
        throw Error("no species loaded: call loadPlantModelFromLibrary first",
                    {.parameter = "species", .validRange = "one of the library species"});
    resolveBuildParameters(*impl_->species, buildParameters);  // range errors up front
    if (impl_->trellisGeometry && impl_->species->trellis)     // and the trellis's
        speciesTrellis(*impl_->species, seed_, impl_->store.nextPlantID, vec3(0.0f),
                       buildParameters);
    const bool together = impl_->collision.world && impl_->collision.world->soft();
    // Plants with attraction points of their own count their work in this scene's stats.
    if (impl_->species->attraction) collision::worldOf(impl_->collision);
    const unsigned first = impl_->store.nextPlantID;
    const int n = int(positions.size());
    const int threads = std::max(1, std::min(omp_get_max_threads(), n));

    std::vector<CanopyWorker> workers(static_cast<std::size_t>(threads));
    for (CanopyWorker& w : workers) {
        w.arch = std::make_unique<PlantArchitecture>(&w.ctx);
        w.arch->seed_ = seed_;
        Impl& wi = *w.arch->impl_;
        wi.store.shootTypes = impl_->store.shootTypes;
        wi.species = impl_->species;
        wi.store.defaultPhenology = impl_->store.defaultPhenology;
        wi.functions = impl_->functions;
        wi.trellisGeometry = false;  // trellises are added in the caller's Context below
        if (!together) wi.collision.world = impl_->collision.world;
    }

    std::vector<int> builtBy(static_cast<std::size_t>(n), -1);
    std::vector<std::string> errors(static_cast<std::size_t>(n));
    auto throwFirstError = [&] {
        for (int i = 0; i < n; ++i)
            if (!errors[std::size_t(i)].empty())
                throw Error("building canopy plant " + std::to_string(i) +
                            " failed: " + errors[std::size_t(i)]);
    };
    std::vector<unsigned> ids;
    // A failed build (or a progress callback that throws: the caller stopping it) leaves the
    // Context as it was: the plants merged so far are deleted again.
    std::exception_ptr stopped;
    auto undo = [&] {
        for (unsigned id : ids) deletePlantInstance(id);
        if (stopped) std::rethrow_exception(stopped);
    };
    if (!together) {
        bool failed = false;
#pragma omp parallel for ordered schedule(dynamic, 1) num_threads(threads)
        for (int i = 0; i < n; ++i) {
            CanopyWorker& worker = workers[std::size_t(omp_get_thread_num())];
            PlantArchitecture& w = *worker.arch;
            const unsigned id = first + unsigned(i);
            try {
                w.impl_->store.nextPlantID = id;  // the plant's ID picks its stream
                w.buildPlantInstanceFromLibrary(positions[std::size_t(i)], age, buildParameters);
            } catch (const std::exception& e) {
                errors[std::size_t(i)] = e.what();
            }
#pragma omp ordered
            {
                if (!errors[std::size_t(i)].empty()) failed = true;
                if (!failed) {
                    mergePlant(worker.ctx, std::move(w.impl_->store.plant(id)), *w.impl_);
                    ids.push_back(id);
                }
                w.impl_->store.plants.erase(id);
                worker.ctx.clear();
                // Progress is told on the calling thread only (OpenMP's thread 0).
                if (!failed && impl_->progress && omp_get_thread_num() == 0) {
                    try {
                        impl_->progress("building", double(ids.size()) / double(n));
                    } catch (...) {
                        stopped = std::current_exception();
                        failed = true;
                    }
                }
            }
        }
        if (stopped || failed) {
            undo();
            throwFirstError();
        }
        if (impl_->progress) impl_->progress("building", 1.0);
        impl_->store.nextPlantID = first + unsigned(n);
        for (unsigned id : ids) addTrellis(id, positions[id - first], buildParameters);
        return ids;
    }

    // Together: build every plant's initial structure in a worker (its geometry is not needed:
    // every plant is tessellated afresh when grown), plant i on thread i % threads, where it
    // grows (collision::growTogether) and is tessellated.
    for (CanopyWorker& w : workers) w.arch->impl_->geometryDeferred = true;
#pragma omp parallel for schedule(static, 1) num_threads(threads)
    for (int i = 0; i < n; ++i) {
        const int t = omp_get_thread_num();
        PlantArchitecture& w = *workers[std::size_t(t)].arch;
        try {
            w.impl_->store.nextPlantID = first + unsigned(i);  // the plant's ID picks its stream
            w.buildPlantStructure(positions[std::size_t(i)], buildParameters);
            builtBy[std::size_t(i)] = t;
        } catch (const std::exception& e) {
            errors[std::size_t(i)] = e.what();
        }
    }
    for (CanopyWorker& w : workers) w.arch->impl_->geometryDeferred = false;
    throwFirstError();

    // Grow them together.
    std::vector<collision::GrowthSlot> slots;
    std::vector<collision::Worker> growers;
    for (CanopyWorker& w : workers) {
        w.arch->impl_->collision.world = impl_->collision.world;
        growers.push_back(w.arch->impl_->worker());
    }
    for (int i = 0; i < n; ++i) {
        Impl& owner = *workers[std::size_t(builtBy[std::size_t(i)])].arch->impl_;
        PlantInstance& plant = owner.store.plant(first + unsigned(i));
        slots.push_back({&plant, collision::attractionFor(owner.collision, plant), {}});
    }
    collision::growTogether(*impl_->collision.world, slots, age, seed_, growers, impl_->progress);

    // Each worker tessellates its own plants; they are merged in plant order as they come (as
    // without avoidance), each worker's Context emptied after each merge.
    bool failed = false;
#pragma omp parallel for ordered schedule(static, 1) num_threads(threads)
    for (int i = 0; i < n; ++i) {
        // The thread's own worker tessellates (whoever built the plant); the plant's owner's
        // maps are only touched in the ordered region.
        CanopyWorker& w = workers[std::size_t(omp_get_thread_num())];
        Impl& owner = *workers[std::size_t(builtBy[std::size_t(i)])].arch->impl_;
        const unsigned id = first + unsigned(i);
        try {
            tessellatePlant(w.arch->impl_->store, w.arch->impl_->prototypes, w.ctx,
                            *slots[std::size_t(i)].plant);
        } catch (const std::exception& e) {
            errors[std::size_t(i)] = e.what();
        }
#pragma omp ordered
        {
            if (!errors[std::size_t(i)].empty()) failed = true;
            if (!failed) {
                mergePlant(w.ctx, std::move(owner.store.plant(id)), owner);
                ids.push_back(id);
            }
            w.ctx.clear();
        }
    }
    if (failed) {
        undo();
        throwFirstError();
    }
    impl_->store.nextPlantID = first + unsigned(n);
    for (unsigned id : ids) addTrellis(id, positions[id - first], buildParameters);
    return ids;
}

std::vector<unsigned> PlantArchitecture::buildPlantCanopyFromLibrary(const CanopyOptions& o,
                                                                     float age) {
    checkCanopyArguments(age, o.germinationRate);
    Rng scene(seed_, kCanopyStream);
    std::vector<vec3> positions;
    if (o.layout == CanopyOptions::Layout::Grid) {
        const glm::ivec2 count = o.count;
        const vec2 spacing = o.spacing;
        if (count.x < 1 || count.y < 1 || std::int64_t(count.x) * count.y > 1000000)
            throw Error("plant count out of range",
                        {.parameter = "plant_count",
                         .value = std::to_string(count.x) + " x " + std::to_string(count.y),
                         .validRange = "at least 1 x 1, at most 1,000,000 plants"});
        if (!(spacing.x > 0.0f && spacing.y > 0.0f) || !std::isfinite(spacing.x) ||
            !std::isfinite(spacing.y))
            throw Error("plant spacing must be positive",
                        {.parameter = "plant_spacing",
                         .value = std::to_string(spacing.x) + " x " + std::to_string(spacing.y),
                         .validRange = "> 0 m in x and y"});
        for (int j = 0; j < count.y; ++j)
            for (int i = 0; i < count.x; ++i) {
                const bool germinates = scene.chance(o.germinationRate);  // one draw per position
                if (!germinates) continue;
                positions.push_back(o.center +
                                    vec3((float(i) - 0.5f * float(count.x - 1)) * spacing.x,
                                         (float(j) - 0.5f * float(count.y - 1)) * spacing.y, 0.0f));
            }
    } else {
        if (o.plants < 1 || o.plants > 1000000)
            throw Error("plant count out of range", {.parameter = "plant_count",
                                                     .value = std::to_string(o.plants),
                                                     .validRange = "1 to 1000000"});
        const vec2 extent = o.extent;
        if (!(extent.x >= 0.0f && extent.y >= 0.0f) || !std::isfinite(extent.x) ||
            !std::isfinite(extent.y))
            throw Error("canopy extent must not be negative",
                        {.parameter = "canopy_extent", .validRange = ">= 0 m in x and y"});
        for (unsigned k = 0; k < o.plants; ++k) {
            const float x = (scene.uniform01() - 0.5f) * extent.x;
            const float y = (scene.uniform01() - 0.5f) * extent.y;
            if (scene.chance(o.germinationRate)) positions.push_back(o.center + vec3(x, y, 0.0f));
        }
    }
    return buildPlantsAt(positions, age, o.buildParameters);
}

std::vector<unsigned> PlantArchitecture::buildPlantCanopyFromLibrary(
    const vec3& center, const vec2& spacing, const glm::ivec2& count, float age, float germination,
    const std::map<std::string, float>& buildParameters) {
    CanopyOptions o;
    o.center = center;
    o.spacing = spacing;
    o.count = count;
    o.germinationRate = germination;
    o.buildParameters = buildParameters;
    return buildPlantCanopyFromLibrary(o, age);
}

}  // namespace plantarch
