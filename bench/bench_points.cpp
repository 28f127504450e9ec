// Point clouds: surface samples drawn and written (binary PLY, .npz), and simulated scans of a
// bean canopy, reported as points or rays a second and MB/s of file (1 MB = 10^6 bytes).

#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>

#include "bench_util.h"
#include "plantarch/Export.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/Scan.h"

using namespace plantarch;

namespace {

// A 5 x 5 bean canopy at 45 days (about 0.9 million triangles).
const Context& canopy() {
    return bench::beanCanopy(5, 5).context();
}

const PointCloud& million() {
    static const PointCloud cloud = samplePoints(canopy(), {.points = 1000000, .seed = 1});
    return cloud;
}

void BM_SamplePoints(benchmark::State& state) {
    const Context& ctx = canopy();
    for (auto _ : state) benchmark::DoNotOptimize(samplePoints(ctx, {.points = 1000000}));
    state.counters["points_per_s"] =
        benchmark::Counter(1e6 * double(state.iterations()), benchmark::Counter::kIsRate);
    state.counters["triangles"] = double(ctx.triangleCount());
}

template <class Write>
void runWrite(benchmark::State& state, const std::string& path, Write&& write) {
    const PointCloud& cloud = million();
    std::uintmax_t bytes = 0;
    for (auto _ : state) {
        write(cloud, path, {});
        state.PauseTiming();
        bytes = std::filesystem::file_size(path);
        state.ResumeTiming();
    }
    state.counters["MB_per_s"] = benchmark::Counter(
        double(bytes) * double(state.iterations()) / 1e6, benchmark::Counter::kIsRate);
    state.counters["file_MB"] = double(bytes) / 1e6;
    std::filesystem::remove(path);
}

void BM_WritePointsPLY(benchmark::State& state) {
    runWrite(state, bench::outputPath("plantarch_bench_points.ply"), writePointCloudPLY);
}

void BM_WritePointsNPZ(benchmark::State& state) {
    runWrite(state, bench::outputPath("plantarch_bench_points.npz"), writePointCloudNPZ);
}

// Two scanners beside the canopy at 0.05 degrees over zenith 40..140 and a full turn: 14.4 M
// rays, on every core.
void BM_Scan(benchmark::State& state) {
    const Context& ctx = canopy();
    ScanOptions o;
    for (const vec3& at : {vec3(1.2f, -0.3f, 1.0f), vec3(-1.2f, 0.4f, 1.0f)}) {
        Scanner s;
        s.origin = at;
        s.zenithMin = 40.0f;
        s.zenithMax = 140.0f;
        s.resolution = 0.05f;
        o.scanners.push_back(s);
    }
    std::size_t points = 0;
    for (auto _ : state) points = scan(ctx, o).positions.size();
    const double rays = double(scanRayCount(o.scanners[0]) * o.scanners.size());
    state.counters["rays_per_s"] =
        benchmark::Counter(rays * double(state.iterations()), benchmark::Counter::kIsRate);
    state.counters["points"] = double(points);
    state.counters["triangles"] = double(ctx.triangleCount());
}

}  // namespace

BENCHMARK(BM_SamplePoints)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(1.0);
BENCHMARK(BM_WritePointsPLY)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(1.0);
BENCHMARK(BM_WritePointsNPZ)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(1.0);
BENCHMARK(BM_Scan)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
