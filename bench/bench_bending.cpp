// Shoots bending under load (plantarch/Bending.h): the cost of one solve for a single shoot
// of 10 to 400 internodes, and for a fruiting library apple tree (docs/performance.md,
// "Bending").

#include <benchmark/benchmark.h>

#include "growth/bending.h"
#include "plantarch/Bending.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;

namespace {

// A horizontal shoot of `n` internodes (1 m in all), bent by its weight from straight.
void bendShoot(benchmark::State& state) {
    const unsigned n = unsigned(state.range(0));
    Context ctx;
    PlantArchitecture arch(&ctx);
    ShootParameters sp;
    sp.phytomer_parameters.internode.pitch = 0.0f;
    arch.defineShootType("stem", sp);
    arch.setGroundClearance(false);
    const unsigned p = arch.addPlantInstance(vec3(0.0f), 0.0f);
    arch.addBaseStemShoot(
        p, {n, {90.0f, 0.0f, 0.0f}, {0.005f, 1.0f / float(n), 1.0f, 1.0f}, 0, "stem"});
    PhenologyParameters ph = arch.plant(p).phenology;
    ph.mechanics.elastic_modulus = 1e9f;
    arch.setPlantPhenologicalThresholds(p, ph);
    for (auto _ : state) {
        state.PauseTiming();
        straightenPlant(arch, p);
        state.ResumeTiming();
        bendPlant(arch, p);
    }
    state.counters["internodes"] = double(n);
    state.counters["tip_drop_mm"] = -1e3 * double(bentNodePositions(arch, p, 0).back().z);
    state.counters["us_per_internode"] =
        benchmark::Counter(double(n) * double(state.iterations()),
                           benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

}  // namespace

static void BM_BendShoot(benchmark::State& s) {
    bendShoot(s);
}
BENCHMARK(BM_BendShoot)->Arg(10)->Arg(50)->Arg(400)->Unit(benchmark::kMicrosecond);

// The library apple at 630 days (75 shoots, 29 fruit): one solve from straight, one from the
// bent state (what growth does after each step), and its build for comparison.
static void BM_BendAppleTree(benchmark::State& state) {
    const bool warm = state.range(0) != 0;
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("apple");
    const unsigned p = arch.buildPlantInstanceFromLibrary(vec3(0.0f), 630.0f);
    std::size_t internodes = 0;
    for (const Shoot& s : arch.plant(p).shoots) internodes += s.phytomers.size();
    bendPlant(arch, p);
    for (auto _ : state) {
        if (!warm) {
            state.PauseTiming();
            straightenPlant(arch, p);
            state.ResumeTiming();
        }
        bendPlant(arch, p);
    }
    state.counters["shoots"] = double(arch.getShootCount(p));
    state.counters["internodes"] = double(internodes);
}
BENCHMARK(BM_BendAppleTree)->ArgName("from_bent")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// The solve alone (no geometry), from straight, leaves of 30 cm2 each.
static void BM_BendAppleTreeSolveOnly(benchmark::State& state) {
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("apple");
    const PlantInstance& plant = arch.plant(arch.buildPlantInstanceFromLibrary(vec3(0.0f), 630.0f));
    const bending::LeafArea area = [](const Phytomer&, const LeafOrgan&) { return 0.003; };
    unsigned iterations = 0;
    for (auto _ : state) {
        const bending::Solution s = bending::solve(plant, plant.phenology.mechanics, area, {});
        iterations = s.iterations;
        benchmark::DoNotOptimize(s.turns.data());
    }
    state.counters["fixed_point_iterations"] = double(iterations);
}
BENCHMARK(BM_BendAppleTreeSolveOnly)->Unit(benchmark::kMillisecond);

// Its build to 630 days, without bending and bent after every growth step.
static void BM_BuildAppleTree(benchmark::State& state) {
    const bool bending = state.range(0) != 0;
    for (auto _ : state) {
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.loadPlantModelFromLibrary("apple");
        PhenologyParameters ph = arch.plant(arch.addPlantInstance(vec3(9.0f), 0.0f)).phenology;
        arch.deletePlantInstance(arch.getAllPlantIDs().back());
        ph.mechanics.enabled = bending;
        arch.setDefaultPhenology(ph);
        benchmark::DoNotOptimize(arch.buildPlantInstanceFromLibrary(vec3(0.0f), 630.0f));
    }
}
BENCHMARK(BM_BuildAppleTree)->ArgName("bending")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
