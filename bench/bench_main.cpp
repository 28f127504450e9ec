// Entry point of plantarch_bench: every bench/*.cpp registers its benchmarks with Google
// Benchmark (the per-species ones here, once the library is initialized). Run
// `build/plantarch_bench --benchmark_filter=NAME` to select some.
#include <benchmark/benchmark.h>

#include "bench_util.h"

int main(int argc, char** argv) {
    plantarch::bench::registerSpeciesBenchmarks();
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
