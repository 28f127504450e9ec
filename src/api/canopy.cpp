// Canopies: many plants of the loaded species, grown in parallel and merged in plant order.
//
// Each thread owns a worker (its own Context and PlantArchitecture with the same species,
// functions and seed) so nothing is shared while plants grow. A plant's numbers depend only
// on its ID (its random stream is Rng::forPlant(seed, ID), the ID counted from the last
// restartPlantStreams) and prototype variants are seeded
// from their parameters, so which worker grows a plant does not matter. The merge then copies
// every plant's objects into the caller's Context in plant order and object order, giving the
// same IDs and bytes whatever the thread count.

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <memory>

#include "api/facade_impl.h"
#include "collision/collision_world.h"
#include "collision/growth_driver.h"
#include "core/parallel.h"
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

}  // namespace

// A plant grown (and tessellated) in a worker: its objects, in ascending ID order, are in
// `context`; its state is in `owner`'s store.
struct PlantArchitecture::GrownPlant {
    unsigned id = 0;
    const Context* context = nullptr;
    Impl* owner = nullptr;
    std::vector<ObjectID> objects;
};

// Copies the objects of grown plants into this Context in one appendObjects call (plant
// order, each plant's objects in ID order, so IDs follow plant order) and takes over their
// state (their own attraction points included), with the object IDs remapped.
void PlantArchitecture::adoptPlants(std::span<GrownPlant> plants) {
    std::vector<ObjectSource> sources;
    std::vector<std::size_t> firstCopy;  // where each plant's objects start among the copies
    sources.reserve(plants.size());
    std::size_t copied = 0;
    for (GrownPlant& g : plants) {
        sources.push_back({g.context, g.objects});
        firstCopy.push_back(copied);
        copied += g.objects.size();
    }
    const std::vector<ObjectID> copies = context_->appendObjects(sources);
    const long count = long(plants.size());
    ParallelErrors errors;
#pragma omp parallel for schedule(dynamic, 4) if (count > 8)
    for (long k = 0; k < count; ++k)
        errors.run(k, [&] {
            GrownPlant& g = plants[std::size_t(k)];
            const ObjectID* base = copies.data() + firstCopy[std::size_t(k)];
            forEachObjectID(g.owner->store.plant(g.id), [&](ObjectID& o) {
                if (o == kNoObject) return;
                const auto at = std::lower_bound(g.objects.begin(), g.objects.end(), o);
                o = base[at - g.objects.begin()];
            });
        });
    errors.rethrow();
    for (GrownPlant& g : plants) {
        PlantInstance plant = std::move(g.owner->store.plant(g.id));
        g.owner->store.plants.erase(g.id);
        g.owner->collision.attractionIndexes.erase(g.id);
        impl_->store.plants.emplace(g.id, std::move(plant));  // with its own attraction points
        impl_->collision.attractionIndexes.erase(g.id);
    }
}

namespace {

// Plants are grown in batches, each plant into a Context of its own (so every plant is
// tessellated into an empty Context, whichever thread grows it), then copied into the scene
// together. A batch holds at most about this many triangles twice (and at least two plants
// per thread). The plant Contexts are kept, with their capacity, from batch to batch: small
// batches keep the memory they touch small, so that the scene's own storage is nearly all the
// canopy's fresh memory (a canopy of 10 x 10 plants at 40 days: batches of 4e6 triangles took 1.9
// times as long on one thread and 1.5 times the memory, most of the difference the kernel's zeroing
// of pages touched for the first time).
constexpr double kBatchTriangles = 1.0e5;

std::vector<ObjectID> plantObjects(PlantInstance& plant) {
    std::vector<ObjectID> objects;
    forEachObjectID(plant, [&](ObjectID& o) {
        if (o != kNoObject) objects.push_back(o);
    });
    std::sort(objects.begin(), objects.end());
    return objects;
}

// The next batch's size from the triangles per plant seen so far. With a triangle limit the
// first batch is one plant per thread: the canopy's estimate, made from it, comes as soon as
// one plant is grown.
int nextBatchSize(int threads, std::size_t triangles, int plants, int left, bool limited) {
    const int least = 2 * threads;
    int size = plants == 0 && limited ? threads : 4 * threads;
    if (plants > 0) {
        const double each = std::max(1.0, double(triangles) / double(plants));
        size = int(std::clamp(kBatchTriangles / each, double(least), 64.0 * threads));
    }
    return std::max(1, std::min(size, left));
}

}  // namespace

// One canopy's build: the plants at `positions`, grown to `age` by worker PlantArchitectures
// (one per thread, each with its own caches) and copied into the scene in plant order.
struct PlantArchitecture::CanopyBuild {
    struct CanopyWorker {
        Context ctx;
        std::unique_ptr<PlantArchitecture> arch;
    };

    PlantArchitecture& arch;
    const std::vector<vec3>& positions;
    float age;
    const std::map<std::string, float>& buildParameters;
    std::size_t limit = 0;                 // the Context's triangle limit (0: none)
    int n = 0;                             // plants
    unsigned first = 0;                    // plant i gets ID first + index(i) ...
    unsigned firstStream = 0;              // ... and random stream firstStream + index(i)
    const std::vector<unsigned>& indices;  // index(i): indices[i], or i when empty
    int threads = 1;
    std::vector<CanopyWorker> workers;
    std::vector<int> builtBy;    // the worker that holds plant i's state
    std::vector<unsigned> ids;   // the plants copied into the scene so far
    std::vector<Context> slots;  // one per plant of a batch, kept (with capacity) for the next
    int nextReport = 0;          // progress within a batch: at most about a hundred reports
    std::size_t trianglesSeen = 0;

    CanopyBuild(PlantArchitecture& a, const std::vector<vec3>& at, float grownTo,
                const std::map<std::string, float>& parameters, bool together,
                const std::vector<unsigned>& only, unsigned count)
        : arch(a), positions(at), age(grownTo), buildParameters(parameters), indices(only) {
        Impl& impl = *arch.impl_;
        limit = arch.context_->triangleLimit();
        impl.store.triangleLimit = limit;
        n = int(positions.size());
        first = arch.context_->reservePlantIDs(std::max(count, unsigned(n)));
        firstStream = impl.store.nextStream;
        threads = std::max(1, std::min(omp_get_max_threads(), n));
        workers.resize(static_cast<std::size_t>(threads));
        for (CanopyWorker& w : workers) {
            w.arch = std::make_unique<PlantArchitecture>(&w.ctx);
            w.arch->seed_ = arch.seed_;
            Impl& wi = *w.arch->impl_;
            wi.store.shootTypes = impl.store.shootTypes;
            wi.species = impl.species;
            wi.store.defaultPhenology = impl.store.defaultPhenology;
            wi.store.meshDetail = impl.store.meshDetail;
            wi.store.groundClearance = impl.store.groundClearance;
            wi.store.groundClipping = impl.store.groundClipping;
            wi.store.organGeometry = impl.store.organGeometry;
            wi.store.triangleLimit = limit;
            wi.functions = impl.functions;
            wi.trellisGeometry = false;  // trellises are added in the caller's Context
            if (!together) wi.collision.world = impl.collision.world;
        }
        builtBy.assign(static_cast<std::size_t>(n), -1);
    }

    Impl& ownerOf(int i) { return *workers[std::size_t(builtBy[std::size_t(i)])].arch->impl_; }
    unsigned index(int i) const { return indices.empty() ? unsigned(i) : indices[std::size_t(i)]; }
    unsigned idOf(int i) const { return first + index(i); }
    unsigned streamOf(int i) const { return firstStream + index(i); }

    // A plant's failure names the plant; a triangle limit passed keeps its own type.
    static void failed(ParallelErrors& errors, int i0) {
        if (!errors.failed()) return;
        const int i = i0 + int(errors.index());
        try {
            errors.rethrow();
        } catch (const TriangleBudgetError&) {
            throw;
        } catch (const std::exception& e) {
            throw Error("building canopy plant " + std::to_string(i) + " failed: " + e.what());
        }
    }

    // The canopy's triangles from the first `built` plants' (`triangles`), refused before
    // any more are grown when over the limit.
    void checkEstimate(std::size_t triangles, int built) const {
        if (limit == 0 || built <= 0 || built >= n) return;
        const double each = double(triangles) / double(built);
        const double total = double(arch.context_->triangleCount()) + each * double(n);
        if (total > double(limit))
            throw TriangleBudgetError("a canopy of " + std::to_string(n) + " plants",
                                      std::size_t(std::ceil(total)), limit,
                                      "about " + std::to_string(std::size_t(std::lround(each))) +
                                          " each, the mean of its first " + std::to_string(built) +
                                          (built == 1 ? " plant" : " plants"));
    }

    // A failed build (or a progress callback that throws: the caller stopping it) leaves the
    // Context as it was: the plants copied so far are deleted again.
    void undo() {
        for (unsigned id : ids) arch.deletePlantInstance(id);
    }

    // Room in the scene for the whole canopy, from the first batch's plants [0, end).
    void reserveFrom(int end) {
        std::size_t objects = 0, vertices = 0, triangles = 0;
        for (int i = 0; i < end; ++i) {
            const Context& slot = slots[std::size_t(i)];
            objects += slot.objectCount();
            vertices += slot.vertexCount();
            triangles += slot.triangleCount();
        }
        const double scale = 1.05 * double(n) / double(end);
        arch.context_->reserve(std::size_t(double(objects) * scale),
                               std::size_t(double(vertices) * scale),
                               std::size_t(double(triangles) * scale));
    }

    // Reports progress; a callback that throws undoes the canopy.
    void report(const char* stage, double fraction) {
        if (!arch.impl_->progress) return;
        try {
            arch.impl_->progress(stage, fraction);
        } catch (...) {
            undo();
            throw;
        }
    }

    // Runs make(i, thread, slot) for every plant in batches on all threads, then copies each
    // batch into the scene.
    template <class Make>
    void inBatches(Make&& make, const char* stage) {
        Impl& impl = *arch.impl_;
        for (int start = 0; start < n;) {
            const int size = nextBatchSize(threads, trianglesSeen, start, n - start, limit > 0);
            const int end = start + size;
            if (slots.size() < std::size_t(size)) slots.resize(std::size_t(size));
            for (Context& slot : slots) slot.setTriangleLimit(limit);
            std::vector<GrownPlant> grown(static_cast<std::size_t>(size));
            ParallelErrors errors;
            // Progress after each plant, reported by the calling thread (OpenMP's thread 0):
            // a callback that throws stops the batch after the plants under way. The batch's
            // last plant is reported with the batch, after it is copied in.
            std::atomic<int> finished{0};
            std::atomic<bool> stop{false};
            std::exception_ptr stopped;
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
            for (int i = start; i < end; ++i) {
                if (stop.load(std::memory_order_relaxed)) continue;
                errors.run(i - start, [&] {
                    const int t = omp_get_thread_num();
                    Context& slot = slots[std::size_t(i - start)];
                    make(i, t, slot);
                    Impl& owner = ownerOf(i);
                    const unsigned id = idOf(i);
                    grown[std::size_t(i - start)] = {id, &slot, &owner,
                                                     plantObjects(owner.store.plant(id))};
                });
                const int done = start + ++finished;
                if (impl.progress && omp_get_thread_num() == 0 && done < end && !stopped &&
                    done >= nextReport) {
                    nextReport = done + std::max(1, n / 100);
                    try {
                        impl.progress(stage, double(done) / double(n));
                    } catch (...) {
                        stopped = std::current_exception();
                        stop = true;
                    }
                }
            }
            if (stopped) {
                undo();
                std::rethrow_exception(stopped);
            }
            try {
                failed(errors, start);
            } catch (...) {
                undo();
                throw;
            }
            for (int i = start; i < end; ++i)
                trianglesSeen += slots[std::size_t(i - start)].triangleCount();
            if (start == 0) checkEstimate(trianglesSeen, end);
            if (start == 0 && end < n) reserveFrom(end);
            try {
                arch.adoptPlants(grown);
            } catch (...) {
                undo();
                throw;
            }
            for (int i = start; i < end; ++i) ids.push_back(idOf(i));
            for (int i = start; i < end; ++i) slots[std::size_t(i - start)].clear(false);
            start = end;
            report(stage, double(start) / double(n));
        }
    }

    // Each batch of plants grown and tessellated on all threads, each into its own Context.
    void growApart() {
        inBatches(
            [&](int i, int t, Context& slot) {
                CanopyWorker& worker = workers[std::size_t(t)];
                PlantArchitecture& w = *worker.arch;
                struct Rebind {  // the plant is tessellated into its own Context
                    PlantArchitecture& arch;
                    Context* home;
                    ~Rebind() { arch.context_ = home; }
                } rebind{w, &worker.ctx};
                w.context_ = &slot;
                w.impl_->store.assignedID = idOf(i);
                w.impl_->store.nextStream = streamOf(i);
                w.buildPlantInstanceFromLibrary(positions[std::size_t(i)], age, buildParameters);
                builtBy[std::size_t(i)] = t;
            },
            "building");
    }

    // With a limit, the estimate before growing together: plant 0 grown alone, without
    // collision avoidance, in a Context of its own (the plants' sizes differ little with it).
    void estimateAlone() {
        if (limit == 0 || n <= 1) return;
        Context probe;
        probe.setTriangleLimit(limit);
        PlantArchitecture& w = *workers[0].arch;
        w.context_ = &probe;
        w.impl_->store.assignedID = idOf(0);
        w.impl_->store.nextStream = streamOf(0);
        std::size_t triangles = 0;
        try {
            const unsigned id = w.buildPlantInstanceFromLibrary(positions[0], age, buildParameters);
            triangles = probe.triangleCount();
            w.deletePlantInstance(id);
        } catch (...) {
            w.context_ = &workers[0].ctx;
            throw;
        }
        w.context_ = &workers[0].ctx;
        checkEstimate(triangles, 1);
    }

    // Every plant's initial structure built in a worker (its geometry is not needed: every
    // plant is tessellated afresh when grown), plant i on thread i % threads, where it grows;
    // then grown together (collision::growTogether) and tessellated in batches by whichever
    // thread is free (the plant's state is only read).
    void growTogether() {
        estimateAlone();
        for (CanopyWorker& w : workers) w.arch->impl_->geometryDeferred = true;
        ParallelErrors structureErrors;
#pragma omp parallel for schedule(static, 1) num_threads(threads)
        for (int i = 0; i < n; ++i)
            structureErrors.run(i, [&] {
                const int t = omp_get_thread_num();
                PlantArchitecture& w = *workers[std::size_t(t)].arch;
                w.impl_->store.assignedID = idOf(i);
                w.impl_->store.nextStream = streamOf(i);
                w.buildPlantStructure(positions[std::size_t(i)], buildParameters);
                builtBy[std::size_t(i)] = t;
            });
        for (CanopyWorker& w : workers) w.arch->impl_->geometryDeferred = false;
        failed(structureErrors, 0);

        Impl& impl = *arch.impl_;
        std::vector<collision::GrowthSlot> growth;
        std::vector<collision::Worker> growers;
        for (CanopyWorker& w : workers) {
            w.arch->impl_->collision.world = impl.collision.world;
            growers.push_back(w.arch->impl_->worker());
        }
        for (int i = 0; i < n; ++i) {
            Impl& owner = ownerOf(i);
            PlantInstance& plant = owner.store.plant(idOf(i));
            growth.push_back({&plant, collision::attractionFor(owner.collision, plant), {}});
        }
        collision::growTogether(*impl.collision.world, growth, age, arch.seed_, growers,
                                impl.progress);
        inBatches(
            [&](int i, int t, Context& slot) {
                Impl& w = *workers[std::size_t(t)].arch->impl_;
                tessellatePlant(w.store, w.prototypes, slot, *growth[std::size_t(i)].plant);
            },
            "tessellating");
    }
};

// With soft collision avoidance the plants must see each other while they grow, so they are
// first built (initial structure only) by the workers, then grown together by
// collision::growTogether (each step on all threads, every plant seeing the scene as it stood
// at the step's start), then tessellated in batches and copied into the scene in plant order.
// Without it, each batch of plants is grown and tessellated on all threads and copied in.
std::vector<unsigned> PlantArchitecture::buildPlantsAt(
    const std::vector<vec3>& positions, float age,
    const std::map<std::string, float>& buildParameters, const std::vector<unsigned>& indices,
    unsigned count) {
    if (!impl_->species)
        throw Error("no species loaded: call loadPlantModelFromLibrary first",
                    {.parameter = "species", .validRange = "one of the library species"});
    resolveBuildParameters(*impl_->species, buildParameters);  // range errors up front
    if (impl_->trellisGeometry && impl_->species->trellis)     // and the trellis's
        speciesTrellis(*impl_->species, seed_, impl_->store.nextStream, vec3(0.0f),
                       buildParameters);
    const bool together = impl_->collision.world && impl_->collision.world->soft();
    // Plants with attraction points of their own count their work in this scene's stats.
    if (impl_->species->attraction) collision::worldOf(impl_->collision);
    CanopyBuild build(*this, positions, age, buildParameters, together, indices, count);
    if (build.n > 0) {
        if (together)
            build.growTogether();
        else
            build.growApart();
    }
    impl_->store.nextStream = build.firstStream + std::max(count, unsigned(build.n));
    for (int i = 0; i < build.n; ++i)
        addTrellis(build.idOf(i), positions[std::size_t(i)], buildParameters);
    return build.ids;
}

std::vector<vec3> canopyPositions(const CanopyOptions& o, std::uint64_t seed) {
    checkCanopyArguments(0.0f, o.germinationRate);
    Rng scene(seed, kCanopyStream);
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
    return positions;
}

std::vector<unsigned> PlantArchitecture::buildPlantCanopyFromLibrary(const CanopyOptions& o,
                                                                     float age) {
    checkCanopyArguments(age, o.germinationRate);
    const std::vector<vec3> positions = canopyPositions(o, seed_);
    if (!o.only) return buildPlantsAt(positions, age, o.buildParameters);
    std::vector<vec3> some;
    for (std::size_t k = 0; k < o.only->size(); ++k) {
        const unsigned i = (*o.only)[k];
        if (i >= positions.size() || (k > 0 && i <= (*o.only)[k - 1]))
            throw Error("canopy plant index out of range or out of order",
                        {.parameter = "only",
                         .value = std::to_string(i),
                         .validRange = "increasing indices below the canopy's " +
                                       std::to_string(positions.size()) + " plants"});
        some.push_back(positions[i]);
    }
    return buildPlantsAt(some, age, o.buildParameters, *o.only, unsigned(positions.size()));
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
