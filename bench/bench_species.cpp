// Every library species built at the age of the reference system's pictures of it
// (bench/data/reference_species.tsv): load, build, grow and tessellate one plant, the
// reference's in-process work per plant. Counters: triangles, leaves, shoots; peak_MiB, the
// peak memory the build adds, measured once in a forked child (its peak resident size minus
// the resident size at the fork); x_reference, the reference's time per plant over this
// one's (how many times faster), and tri_ratio, triangles over the reference's mean.
//
//   build/plantarch_bench --benchmark_filter=Species/ --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true   (one line)

#include <benchmark/benchmark.h>
#include <malloc.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "bench_util.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/SpeciesIO.h"

using namespace plantarch;

namespace {

unsigned buildOne(PlantArchitecture& arch, const std::string& name, float age) {
    arch.loadPlantModelFromLibrary(name);
    return arch.buildPlantInstanceFromLibrary(vec3(0.0f), age);
}

// A field of /proc/self/status in bytes ("VmHWM", "VmRSS"); 0 if unreadable.
double statusBytes(const char* field) {
    std::FILE* f = std::fopen("/proc/self/status", "r");
    if (!f) return 0.0;
    char line[256];
    double kib = 0.0;
    const std::size_t n = std::strlen(field);
    while (std::fgets(line, sizeof line, f))
        if (std::strncmp(line, field, n) == 0 && line[n] == ':') kib = std::atof(line + n + 1);
    std::fclose(f);
    return kib * 1024.0;
}

// Peak extra memory of one build, in MiB, measured in a child process: its peak resident
// size is reset (clear_refs 5) after the heap left by earlier builds is trimmed, then the build's
// peak over the starting size is reported through a pipe. -1 if anything fails.
double peakMiB(const std::string& name, float age) {
    int fds[2];
    if (pipe(fds) != 0) return -1.0;
    const pid_t pid = fork();
    if (pid < 0) return -1.0;
    if (pid == 0) {
        close(fds[0]);
        double mib = -1.0;
        malloc_trim(0);  // give back the heap the parent freed, so the build's pages count
        if (std::FILE* c = std::fopen("/proc/self/clear_refs", "w")) {
            std::fputs("5", c);
            std::fclose(c);
            const double start = statusBytes("VmRSS");
            {
                Context ctx;
                PlantArchitecture arch(&ctx);
                buildOne(arch, name, age);
            }
            mib = (statusBytes("VmHWM") - start) / (1024.0 * 1024.0);
        }
        const ssize_t written = write(fds[1], &mib, sizeof mib);
        _exit(written == ssize_t(sizeof mib) ? 0 : 1);
    }
    close(fds[1]);
    double mib = -1.0;
    if (read(fds[0], &mib, sizeof mib) != ssize_t(sizeof mib)) mib = -1.0;
    close(fds[0]);
    int status = 0;
    waitpid(pid, &status, 0);
    return mib;
}

// The reference system's figures for one species at its picture age.
struct ReferencePlant {
    std::string name;
    float age = 0.0f;
    double ms = 0.0;         // in-process build time per plant, one thread
    double triangles = 0.0;  // mean over its seeds 1 to 5
};

std::vector<ReferencePlant> readReferencePlants() {
    const std::string path = PLANTARCH_BENCH_DATA_DIR "/reference_species.tsv";
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot be read");
    std::vector<ReferencePlant> out;
    std::string line;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream cells(line);
        ReferencePlant r;
        if (!(cells >> r.name >> r.age >> r.ms >> r.triangles))
            throw std::runtime_error(path + ": a malformed row: " + line);
        out.push_back(r);
    }
    return out;
}

void buildSpecies(benchmark::State& state, const ReferencePlant& ref) {
    std::size_t triangles = 0, leaves = 0, shoots = 0;
    double seconds = 0.0;
    for (auto _ : state) {
        const auto start = std::chrono::steady_clock::now();
        Context ctx;
        PlantArchitecture arch(&ctx);
        const unsigned p = buildOne(arch, ref.name, ref.age);
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        triangles = ctx.triangleCount();
        leaves = arch.getPlantLeafCount(p);
        shoots = arch.plant(p).shoots.size();
    }
    state.counters["age_d"] = ref.age;
    state.counters["triangles"] = double(triangles);
    state.counters["leaves"] = double(leaves);
    state.counters["shoots"] = double(shoots);
    state.counters["peak_MiB"] = peakMiB(ref.name, ref.age);
    if (ref.ms > 0.0) {
        state.counters["x_reference"] = ref.ms * 1e-3 / (seconds / double(state.iterations()));
        state.counters["tri_ratio"] = double(triangles) / ref.triangles;
    }
}

}  // namespace

// One benchmark per library species (called from main: reading species files needs the
// library's static tables, which are not ready during static construction). A species without
// a reference row is built at the default of its recommended ages, with no ratios.
void plantarch::bench::registerSpeciesBenchmarks() {
    static const std::vector<ReferencePlant> reference = readReferencePlants();
    for (const std::string& name : listSpecies()) {
        const ReferencePlant* ref = nullptr;
        for (const ReferencePlant& r : reference)
            if (r.name == name) ref = &r;
        if (ref) {
            benchmark::RegisterBenchmark(("Species/" + name).c_str(), buildSpecies, *ref)
                ->Unit(benchmark::kMillisecond);
        } else {
            ReferencePlant own{name, loadSpecies(name).recommendedAge, 0.0, 0.0};
            benchmark::RegisterBenchmark(("Species/" + name).c_str(), buildSpecies, own)
                ->Unit(benchmark::kMillisecond);
        }
    }
}
