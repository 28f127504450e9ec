// Export throughput: a 4-million-triangle scene (40,000 leaf-like objects of 100 triangles
// with UVs, labelled with plantID and organ) written as OBJ+MTL and PLY into /tmp (or
// $PLANTARCH_BENCH_DIR). Reported as MB/s of file written (1 MB = 10^6 bytes), wall-clock
// time, on all threads (OBJ formats on every core, GLB computes normals on every core; PLY
// is one thread). Targets: OBJ >= 800 MB/s, binary PLY and GLB >= 1000 MB/s.

#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <string>

#include "bench_util.h"
#include "plantarch/Context.h"
#include "plantarch/Export.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;

namespace {

const Context& scene4M() {
    static const Context ctx = [] {
        Context c;
        const Mesh leaf = bench::leafGrid(10, 5);  // 100 triangles, 66 vertices
        const MaterialID green = c.addMaterial({.color = {0.2f, 0.5f, 0.1f}, .name = "leaf"});
        const MaterialID dark = c.addMaterial({.color = {0.1f, 0.3f, 0.05f}, .name = "old_leaf"});
        for (int i = 0; i < 40000; ++i) {
            // 100 plants of 400 leaves, spread over 10 x 10 m, leaves around a 1.5 m stem.
            const int plant = i / 400, k = i % 400;
            mat4 m = glm::translate(
                mat4(1.0f), vec3(float(plant % 10), float(plant / 10), 0.05f + 0.0037f * float(k)));
            m = glm::rotate(m, glm::radians(137.5f * float(k)), vec3(0, 0, 1));
            m = glm::rotate(m, glm::radians(-30.0f), vec3(0, 1, 0));
            Mesh placed = leaf;
            placed.transform(m);
            const ObjectID id = c.addObject(placed, k % 7 == 0 ? dark : green);
            c.setObjectData(id, "plantID", plant);
            c.setObjectData(id, "organ", std::string("leaf"));
        }
        return c;
    }();
    return ctx;
}

template <class Write>
void runExport(benchmark::State& state, const std::string& path, Write&& write) {
    const Context& ctx = scene4M();
    std::uintmax_t bytes = 0;
    for (auto _ : state) {
        write(ctx, path);
        state.PauseTiming();
        bytes = std::filesystem::file_size(path);
        state.ResumeTiming();
    }
    state.SetBytesProcessed(static_cast<std::int64_t>(bytes * state.iterations()));
    state.counters["MB_per_s"] = benchmark::Counter(
        double(bytes) * double(state.iterations()) / 1e6, benchmark::Counter::kIsRate);
    state.counters["file_MB"] = double(bytes) / 1e6;
    state.counters["triangles"] = double(ctx.triangleCount());
    std::filesystem::remove(path);
    std::filesystem::remove(std::filesystem::path(path).replace_extension(".mtl"));
}

void BM_ExportOBJ(benchmark::State& state) {
    runExport(state, bench::outputPath("plantarch_bench_export.obj"),
              [](const Context& c, const std::string& p) { writeOBJ(c, p); });
}

void BM_ExportOBJNoNormals(benchmark::State& state) {
    runExport(state, bench::outputPath("plantarch_bench_export_nonormals.obj"),
              [](const Context& c, const std::string& p) { writeOBJ(c, p, {.normals = false}); });
}

void BM_ExportPLYBinary(benchmark::State& state) {
    runExport(state, bench::outputPath("plantarch_bench_export.ply"),
              [](const Context& c, const std::string& p) { writePLY(c, p); });
}

void BM_ExportPLYAscii(benchmark::State& state) {
    runExport(state, bench::outputPath("plantarch_bench_export_ascii.ply"),
              [](const Context& c, const std::string& p) {
                  writePLY(c, p, {.format = PlyFormat::Ascii});
              });
}

void BM_ExportGLB(benchmark::State& state) {
    runExport(state, bench::outputPath("plantarch_bench_export.glb"),
              [](const Context& c, const std::string& p) { writeGLTF(c, p); });
}

// A real canopy: 150 library beans at 45 days (about 5 million triangles), with the plant
// nodes named and placed.
void BM_ExportGLBBeanCanopy(benchmark::State& state) {
    PlantArchitecture& arch = bench::beanCanopy(15, 10);
    const Context& ctx = arch.context();
    GltfOptions o;
    for (unsigned id : arch.getAllPlantIDs())
        o.plants.push_back({std::int32_t(id), "bean", arch.getPlantBasePosition(id), 45.0, 42});
    const std::string path = bench::outputPath("plantarch_bench_canopy.glb");
    std::uintmax_t bytes = 0;
    for (auto _ : state) {
        writeGLTF(ctx, path, o);
        state.PauseTiming();
        bytes = std::filesystem::file_size(path);
        state.ResumeTiming();
    }
    state.counters["MB_per_s"] = benchmark::Counter(
        double(bytes) * double(state.iterations()) / 1e6, benchmark::Counter::kIsRate);
    state.counters["file_MB"] = double(bytes) / 1e6;
    state.counters["triangles"] = double(ctx.triangleCount());
    std::filesystem::remove(path);
}

}  // namespace

BENCHMARK(BM_ExportGLB)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_ExportGLBBeanCanopy)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_ExportOBJ)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_ExportOBJNoNormals)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_ExportPLYBinary)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_ExportPLYAscii)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
