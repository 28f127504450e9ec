// Plant structure files and plant strings: writing and reading the library bean at 50 days
// (the figures docs/performance.md quotes). Reading includes building the plant's geometry;
// the "state only" case stops at the plant state (parsing, checks, no tessellation).

#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>

#include "plant_io/plant_structure.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;

namespace {

struct Bean {
    Context ctx;
    PlantArchitecture arch{&ctx};
    unsigned id = 0;
    std::string path;
    Bean() {
        arch.loadPlantModelFromLibrary("bean");
        id = arch.buildPlantInstanceFromLibrary(vec3(0.0f), 50.0f);
        path = (std::filesystem::temp_directory_path() / "plantarch_bench_bean50.xml").string();
        arch.writePlantStructureXML(id, path);
    }
};

Bean& bean() {
    static Bean b;
    return b;
}

}  // namespace

static void BM_BeanXMLWriteFile(benchmark::State& state) {
    Bean& b = bean();
    for (auto _ : state) b.arch.writePlantStructureXML(b.id, b.path);
    state.counters["bytes"] = double(std::filesystem::file_size(b.path));
}
BENCHMARK(BM_BeanXMLWriteFile)->Unit(benchmark::kMillisecond);

static void BM_BeanXMLReadFile(benchmark::State& state) {
    Bean& b = bean();
    std::size_t triangles = 0;
    for (auto _ : state) {
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.readPlantStructureXML(b.path);
        triangles = ctx.triangleCount();
    }
    state.counters["triangles"] = double(triangles);
}
BENCHMARK(BM_BeanXMLReadFile)->Unit(benchmark::kMillisecond);

static void BM_BeanXMLReadStateOnly(benchmark::State& state) {
    Bean& b = bean();
    const std::string text = b.arch.getPlantStructureXML({b.id});
    const std::map<std::string, ShootParameters> none;
    plant_io::Defaults d;
    d.shootTypes = &none;
    for (auto _ : state) {
        auto read = plant_io::readPlantsXML(text, "bean.xml", d);
        benchmark::DoNotOptimize(read);
    }
}
BENCHMARK(BM_BeanXMLReadStateOnly)->Unit(benchmark::kMillisecond);

static void BM_BeanPlantStringWriteRead(benchmark::State& state) {
    Bean& b = bean();
    std::size_t bytes = 0;
    for (auto _ : state) {
        const std::string s = b.arch.getPlantString(b.id);
        bytes = s.size();
        const unsigned q = b.arch.generatePlantFromString(s);
        b.arch.deletePlantInstance(q);
    }
    state.counters["bytes"] = double(bytes);
}
BENCHMARK(BM_BeanPlantStringWriteRead)->Unit(benchmark::kMillisecond);
