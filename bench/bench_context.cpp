// Context insertion rate and memory: 10 million triangles in objects of 100 triangles, each
// object labelled as a plant organ would be (plantID, organ, leafID, age).

#include <benchmark/benchmark.h>

#include <glm/gtc/matrix_transform.hpp>

#include "bench_util.h"
#include "plantarch/Context.h"

using namespace plantarch;

static void BM_ContextAdd10MTriangles(benchmark::State& state) {
    const Mesh leaf = bench::leafGrid(10, 5);  // 100 triangles, 66 vertices
    const std::size_t objects = 100000;        // 10 million triangles
    for (auto _ : state) {
        const std::size_t before = bench::residentBytes();
        Context ctx;
        const MaterialID green = ctx.addMaterial({.color = {0.2f, 0.5f, 0.1f}});
        for (std::size_t i = 0; i < objects; ++i) {
            const ObjectID id = ctx.addObject(leaf, green);
            ctx.setObjectData(id, "plantID", static_cast<int>(i / 400));
            ctx.setObjectData(id, "organ", std::string("leaf"));
            ctx.setObjectData(id, "leafID", static_cast<int>(i));
            ctx.setObjectData(id, "age", 10.0f);
        }
        const std::size_t after = bench::residentBytes();
        benchmark::DoNotOptimize(ctx.triangleCount());
        state.counters["bytes_per_triangle_rss"] =
            double(after - before) / double(ctx.triangleCount());
        state.counters["bytes_per_triangle_ctx"] =
            double(ctx.memoryBytes()) / double(ctx.triangleCount());
    }
    state.counters["triangles_per_s"] =
        benchmark::Counter(double(objects * leaf.triangleCount()) * double(state.iterations()),
                           benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ContextAdd10MTriangles)->Unit(benchmark::kMillisecond)->Iterations(3);

static void BM_ContextIterateTriangles(benchmark::State& state) {
    const Mesh leaf = bench::leafGrid(10, 5);
    Context ctx;
    for (int i = 0; i < 20000; ++i) ctx.addObject(leaf);  // 2 million triangles
    for (auto _ : state) {
        double area = 0.0;
        ctx.forEachObject([&](const ObjectView& v) {
            for (std::size_t t = 0; t < v.indices.size(); t += 3) {
                const vec3& a = v.positions[v.indices[t]];
                const vec3& b = v.positions[v.indices[t + 1]];
                const vec3& c = v.positions[v.indices[t + 2]];
                area += 0.5 * glm::length(glm::cross(b - a, c - a));
            }
        });
        benchmark::DoNotOptimize(area);
    }
    state.counters["triangles_per_s"] = benchmark::Counter(
        double(ctx.triangleCount()) * double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ContextIterateTriangles)->Unit(benchmark::kMillisecond);
