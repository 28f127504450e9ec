// Preview renderer on a 4-million-triangle canopy (40,000 leaf meshes of 100 triangles) at
// 1024x768: the BVH build (RenderScene) and the ray casting (RenderScene::render) timed apart,
// then the one-shot render() that does both.

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <glm/gtc/matrix_transform.hpp>

#include "bench_util.h"
#include "plantarch/Context.h"
#include "plantarch/Random.h"
#include "plantarch/Render.h"

using namespace plantarch;

namespace {

/// 40,000 leaves scattered over a 10 m x 10 m field between 0.1 and 0.9 m high, with random
/// yaw and pitch, plus a stem tube-like box per 100 leaves. Built once.
const Context& canopy() {
    static const Context ctx = [] {
        Context c;
        const Mesh leaf = bench::leafGrid(10, 5);  // 100 triangles
        const MaterialID green = c.addMaterial({.color = {0.22f, 0.50f, 0.14f}});
        Rng rng(7);
        constexpr int side = 200;  // 200 x 200 = 40,000 leaves
        for (int i = 0; i < side; ++i)
            for (int j = 0; j < side; ++j) {
                mat4 xf = glm::translate(mat4(1.0f), vec3(0.05f * float(i) + rng.uniform(0, 0.05f),
                                                          0.05f * float(j) + rng.uniform(0, 0.05f),
                                                          rng.uniform(0.1f, 0.9f)));
                xf = glm::rotate(xf, rng.uniform(0.0f, 6.2831853f), vec3(0, 0, 1));
                xf = glm::rotate(xf, rng.uniform(-0.6f, 0.3f), vec3(0, 1, 0));
                Mesh m = leaf;
                m.transform(xf);
                const ObjectID id = c.addObject(m, green);
                c.setObjectData(id, "organ", std::string("leaf"));
            }
        return c;
    }();
    return ctx;
}

void setCounters(benchmark::State& state, const RenderOptions& o) {
    state.counters["triangles"] = double(canopy().triangleCount());
    state.counters["pixels_per_s"] =
        benchmark::Counter(double(o.width) * double(o.height) * double(state.iterations()),
                           benchmark::Counter::kIsRate);
}

}  // namespace

static void BM_RenderBuildBVH4M(benchmark::State& state) {
    const Context& ctx = canopy();
    for (auto _ : state) {
        RenderScene scene(ctx);
        benchmark::DoNotOptimize(scene.triangleCount());
    }
    state.counters["triangles"] = double(ctx.triangleCount());
    state.counters["triangles_per_s"] = benchmark::Counter(
        double(ctx.triangleCount()) * double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RenderBuildBVH4M)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

static void BM_RenderTraceShaded4M(benchmark::State& state) {
    const RenderScene scene(canopy());
    RenderOptions o;
    for (auto _ : state) benchmark::DoNotOptimize(scene.render(o).rgb.data());
    setCounters(state, o);
}
BENCHMARK(BM_RenderTraceShaded4M)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

static void BM_RenderTraceLabel4M(benchmark::State& state) {
    const RenderScene scene(canopy());
    RenderOptions o;
    o.mode = RenderMode::LabelObject;
    for (auto _ : state) benchmark::DoNotOptimize(scene.render(o).rgb.data());
    setCounters(state, o);
}
BENCHMARK(BM_RenderTraceLabel4M)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

static void BM_RenderOneShot4M(benchmark::State& state) {
    RenderOptions o;
    Image image;
    for (auto _ : state) {
        image = render(canopy(), o);
        benchmark::DoNotOptimize(image.rgb.data());
    }
    setCounters(state, o);
    // PLANTARCH_BENCH_PNG=path keeps a look at what was rendered.
    if (const char* path = std::getenv("PLANTARCH_BENCH_PNG")) writePNG(image, path);
}
BENCHMARK(BM_RenderOneShot4M)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
