// advanceTime cost: a branching, flowering plant grown 60 days in one call, in daily calls
// and in 0.1-day calls. Reports time per phytomer created and the plant's size.

#include <benchmark/benchmark.h>

#include "bench_util.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;

namespace {

ShootParameters branchingShoot() {
    ShootParameters s;
    auto& p = s.phytomer_parameters;
    p.internode.pitch = 0.0f;
    p.internode.phyllotactic_angle = RandomFloat::uniform(130, 150);
    p.internode.radius_initial = 0.002f;
    p.internode.max_vegetative_buds_per_petiole = 1;
    p.internode.max_floral_buds_per_petiole = 1;
    p.petiole.length = 0.04f;
    p.petiole.pitch = RandomFloat::normal(50, 8);
    p.leaf.prototype_scale = 0.05f;
    p.leaf.leaves_per_petiole = 3;
    p.leaf.leaflet_offset = 0.3f;
    p.inflorescence.flowers_per_peduncle = RandomInt::uniform(1, 3);
    p.inflorescence.flower_offset = 0.3f;
    s.max_nodes = 20;
    s.phyllochron_min = 1.5f;
    s.elongation_rate_max = 0.1f;
    s.internode_length_max = 0.03f;
    s.tortuosity = 5.0f;
    s.gravitropic_curvature = 50.0f;
    s.girth_area_factor = 20.0f;
    // Without a winter a negative decay gives every bud the minimum: 0.25 makes the plant
    // branch to about 230 shoots by day 60.
    s.vegetative_bud_break_probability_min = 0.25f;
    s.vegetative_bud_break_probability_max = 0.6f;
    s.vegetative_bud_break_probability_decay_rate = -0.25f;
    s.vegetative_bud_break_time = RandomFloat::uniform(3, 9);
    s.flower_bud_break_probability = 0.6f;
    s.fruit_set_probability = 0.5f;
    s.determinate_shoot_growth = false;
    return s;
}

void growIn(benchmark::State& state, int calls) {
    std::size_t phytomers = 0, triangles = 0, shoots = 0;
    for (auto _ : state) {
        Context ctx;
        PlantArchitecture arch(&ctx);
        PhenologyParameters ph;
        ph.time_to_flower_initiation = 25;
        ph.time_to_flower_opening = 4;
        ph.time_to_fruit_set = 4;
        ph.time_to_fruit_maturity = 15;
        arch.setDefaultPhenology(ph);
        arch.defineShootType("main", branchingShoot());
        const unsigned p = arch.addPlantInstance(vec3(0.0f), 0.0f);
        arch.addBaseStemShoot(p, {1, {}, {0.002f, 0.03f, 0.01f, 0.01f}, 0, "main"});
        for (int i = 0; i < calls; ++i) arch.advanceTime(60.0 / calls);
        phytomers = 0;
        for (const Shoot& s : arch.plant(p).shoots) phytomers += s.phytomers.size();
        shoots = arch.getShootCount(p);
        triangles = ctx.triangleCount();
    }
    state.counters["phytomers"] = double(phytomers);
    state.counters["shoots"] = double(shoots);
    state.counters["triangles"] = double(triangles);
    state.counters["us_per_phytomer"] =
        benchmark::Counter(double(phytomers) * double(state.iterations()),
                           benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

}  // namespace

static void BM_Grow60Days_OneCall(benchmark::State& s) {
    growIn(s, 1);
}
static void BM_Grow60Days_DailyCalls(benchmark::State& s) {
    growIn(s, 60);
}
static void BM_Grow60Days_TenthDayCalls(benchmark::State& s) {
    growIn(s, 600);
}
BENCHMARK(BM_Grow60Days_OneCall)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Grow60Days_DailyCalls)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Grow60Days_TenthDayCalls)->Unit(benchmark::kMillisecond)->Iterations(1);

// The library bean grown to 50 days (load, build, grow, tessellate), for comparison with
// other tools' per-plant build times.
static void BM_LibraryBean50Days(benchmark::State& state) {
    std::size_t triangles = 0, leaves = 0;
    for (auto _ : state) {
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.loadPlantModelFromLibrary("bean");
        const unsigned p = arch.buildPlantInstanceFromLibrary(vec3(0.0f), 50.0f);
        triangles = ctx.triangleCount();
        leaves = arch.getPlantLeafCount(p);
    }
    state.counters["triangles"] = double(triangles);
    state.counters["leaves"] = double(leaves);
}
BENCHMARK(BM_LibraryBean50Days)->Unit(benchmark::kMillisecond);

// A 10 x 10 canopy of library beans at 40 days, grown on the given number of threads (0:
// all cores), so one run gives the ratio of one thread to two.
static void BM_BeanCanopy10x10At40Days(benchmark::State& state) {
    const plantarch::bench::ThreadCount threads(int(state.range(0)));
    std::size_t triangles = 0;
    for (auto _ : state) {
        const std::size_t before = plantarch::bench::residentBytes();
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.loadPlantModelFromLibrary("bean");
        arch.buildPlantCanopyFromLibrary(vec3(0.0f), vec2(0.3f, 0.3f), glm::ivec2(10, 10), 40.0f);
        triangles = ctx.triangleCount();
        state.counters["rss_growth_MiB"] =
            double(plantarch::bench::residentBytes() - before) / (1024.0 * 1024.0);
    }
    state.counters["triangles"] = double(triangles);
}
BENCHMARK(BM_BeanCanopy10x10At40Days)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
