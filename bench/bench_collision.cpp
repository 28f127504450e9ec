// Collision avoidance: the bean canopy with soft avoidance (compare BM_BeanCanopy10x10At40Days)
// and the cost of refreshing the collision scene.

#include <benchmark/benchmark.h>

#include "bench_util.h"
#include "collision/cone.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;

namespace {

void reportCollision(benchmark::State& state, const CollisionStats& st) {
    state.counters["cones"] = double(st.softCones);
    state.counters["rays"] = double(st.softRays);
    state.counters["steered"] = double(st.softSteered);
    state.counters["refreshes"] = double(st.sceneRefreshes);
    state.counters["plants_rebuilt"] = double(st.plantsRebuilt);
    state.counters["plants_kept"] = double(st.plantsUnchanged);
    state.counters["proxy_triangles"] = double(st.sceneTriangles);
    state.counters["refresh_ms_total"] = st.refreshSeconds * 1e3;
    state.counters["cone_thread_ms"] = st.coneSeconds * 1e3;
    state.counters["refresh_ms_each"] =
        st.sceneRefreshes ? st.refreshSeconds * 1e3 / double(st.sceneRefreshes) : 0.0;
}

}  // namespace

// The 10 x 10 bean canopy at 40 days (0.3 m grid) with soft collision avoidance: cone 80
// degrees, 0.1 m, inertia 0.4, leaves as obstacles, and the number of rays and the scene's
// update interval (tenths of a day) given as arguments (defaults: 256 rays, every day), and
// the cone kernel (1: the widest the processor runs, the default; 0: the portable one), and
// the thread count (0: all cores).
static void BM_BeanCanopy10x10At40DaysSoftAvoidance(benchmark::State& state) {
    const plantarch::bench::ThreadCount threads(int(state.range(3)));
    CollisionStats st;
    std::size_t triangles = 0;
    SoftCollisionOptions options;
    options.cone.rays = unsigned(state.range(0));
    options.updateInterval = double(state.range(1)) / 10.0;
    struct Kernel {
        explicit Kernel(bool portable) {
            if (portable) collision::setConeKernel(collision::ConeKernel::kPortable);
        }
        ~Kernel() { collision::setConeKernel(std::nullopt); }
    } kernel(state.range(2) == 0);
    state.counters["wide_kernel"] = collision::coneKernel() == collision::ConeKernel::kWide;
    for (auto _ : state) {
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.loadPlantModelFromLibrary("bean");
        arch.enableSoftCollisionAvoidance(options);
        arch.buildPlantCanopyFromLibrary(vec3(0.0f), vec2(0.3f, 0.3f), glm::ivec2(10, 10), 40.0f);
        st = arch.getCollisionStats();
        triangles = ctx.triangleCount();
    }
    reportCollision(state, st);
    state.counters["triangles"] = double(triangles);
}
BENCHMARK(BM_BeanCanopy10x10At40DaysSoftAvoidance)
    ->ArgNames({"rays", "interval_tenths", "kernel", "threads"})
    ->Args({256, 10, 1, 1})
    ->Args({256, 10, 1, 2})
    ->Args({64, 10, 1, 0})
    ->Args({256, 20, 1, 0})
    ->Args({256, 10, 0, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// One more day of the grown canopy: growth of 100 plants, one scene refresh (every plant's
// proxies placed again where they grew, the grid rebuilt), tessellation.
static void BM_SoftCanopyOneMoreDay(benchmark::State& state) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    arch.enableSoftCollisionAvoidance();
    arch.buildPlantCanopyFromLibrary(vec3(0.0f), vec2(0.3f, 0.3f), glm::ivec2(10, 10), 40.0f);
    arch.resetCollisionStats();
    for (auto _ : state) arch.advanceTime(1.0);
    reportCollision(state, arch.getCollisionStats());
}
BENCHMARK(BM_SoftCanopyOneMoreDay)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(5);

// Refreshing a scene whose plants did not change: every plant's proxies are gathered and
// compared (all kept), the grid is rebuilt (plants past their last phytomer: a 0-day step
// after a refresh).
static void BM_SoftSceneRefreshUnchanged(benchmark::State& state) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    arch.enableSoftCollisionAvoidance();
    arch.buildPlantCanopyFromLibrary(vec3(0.0f), vec2(0.3f, 0.3f), glm::ivec2(10, 10), 40.0f);
    const std::vector<unsigned> ids = arch.getAllPlantIDs();
    arch.resetCollisionStats();
    for (auto _ : state) {
        state.PauseTiming();
        for (unsigned id : ids) arch.updateGeometry(id);  // marks every plant for a re-read
        state.ResumeTiming();
        arch.advanceTime(0.0);  // re-reads them: nothing changed, every plant kept
    }
    reportCollision(state, arch.getCollisionStats());
}
BENCHMARK(BM_SoftSceneRefreshUnchanged)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(5);
