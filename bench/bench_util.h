#pragma once
// Helpers shared by the benchmarks: resident memory, thread counts and synthetic leaf-like
// meshes.

#include <omp.h>
#include <unistd.h>

#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>
#include <utility>

#include "plantarch/Mesh.h"
#include "plantarch/PlantArchitecture.h"

namespace plantarch::bench {

/// Where the file benchmarks write: $PLANTARCH_BENCH_DIR, or /tmp. Point it at a tmpfs
/// (/dev/shm) to time the writers without the disk.
// Runs the enclosing scope on `threads` OpenMP threads (0: as many as the machine has).
class ThreadCount {
public:
    explicit ThreadCount(int threads) : saved_(omp_get_max_threads()) {
        if (threads > 0) omp_set_num_threads(threads);
    }
    ~ThreadCount() { omp_set_num_threads(saved_); }
    ThreadCount(const ThreadCount&) = delete;
    ThreadCount& operator=(const ThreadCount&) = delete;

private:
    int saved_;
};

inline std::string outputPath(const std::string& name) {
    const char* dir = std::getenv("PLANTARCH_BENCH_DIR");
    return std::string(dir && *dir ? dir : "/tmp") + "/" + name;
}

/// A scene of library beans at 45 days, nx x ny at 0.3 m spacing; each size is built once per
/// process and kept.
inline PlantArchitecture& beanCanopy(int nx, int ny) {
    struct Scene {
        Context ctx;
        PlantArchitecture arch{&ctx};
    };
    static std::map<std::pair<int, int>, std::unique_ptr<Scene>> built;
    std::unique_ptr<Scene>& s = built[{nx, ny}];
    if (!s) {
        s = std::make_unique<Scene>();
        s->arch.loadPlantModelFromLibrary("bean");
        s->arch.buildPlantCanopyFromLibrary(vec3(0.0f), vec2(0.3f), glm::ivec2(nx, ny), 45.0f);
    }
    return s->arch;
}

/// Registers one benchmark per library species (bench_species.cpp).
void registerSpeciesBenchmarks();

/// Resident set size of this process in bytes (from /proc/self/statm).
inline std::size_t residentBytes() {
    std::FILE* f = std::fopen("/proc/self/statm", "r");
    if (!f) return 0;
    unsigned long size = 0, resident = 0;
    const int n = std::fscanf(f, "%lu %lu", &size, &resident);
    std::fclose(f);
    return n == 2 ? resident * static_cast<std::size_t>(sysconf(_SC_PAGESIZE)) : 0;
}

/// A leaf-like grid of nx*ny quads (2*nx*ny triangles) with UVs, 10 cm long, gently curved.
inline Mesh leafGrid(int nx = 10, int ny = 5) {
    Mesh m;
    for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i) {
            const float u = float(i) / nx, v = float(j) / ny;
            m.positions.push_back({0.1f * u, 0.04f * (v - 0.5f), 0.01f * u * u});
            m.uvs.push_back({u, v});
        }
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const std::uint32_t a = j * (nx + 1) + i, b = a + 1, c = a + nx + 1, d = c + 1;
            m.indices.insert(m.indices.end(), {a, b, d, a, d, c});
        }
    return m;
}

}  // namespace plantarch::bench
