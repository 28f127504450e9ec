// Entry point of plantarch_bench: every bench/*.cpp registers its benchmarks with Google
// Benchmark. Run `build/plantarch_bench --benchmark_filter=NAME` to select some.
#include <benchmark/benchmark.h>

BENCHMARK_MAIN();
