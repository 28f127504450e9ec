// The 10 x 10 bean canopy at 40 days, with or without soft collision avoidance, once: a
// program for counting instructions (docs/performance.md, "Collision avoidance"):
//
//   OMP_NUM_THREADS=1 valgrind --tool=callgrind build/plantarch_soft_canopy none
//   OMP_NUM_THREADS=1 valgrind --tool=callgrind build/plantarch_soft_canopy soft
//
// With a second argument `checksum` it also prints a checksum of every vertex, to check that
// a change leaves the plants the same to the bit (not counted in the numbers of the docs).

#include <cstdint>
#include <cstdio>
#include <cstring>

#include "plantarch/PlantArchitecture.h"

using namespace plantarch;

int main(int argc, char** argv) {
    const bool usage = argc < 2 || argc > 3 ||
                       (std::strcmp(argv[1], "none") != 0 && std::strcmp(argv[1], "soft") != 0) ||
                       (argc == 3 && std::strcmp(argv[2], "checksum") != 0);
    if (usage) {
        std::fprintf(stderr, "usage: plantarch_soft_canopy none|soft [checksum]\n");
        return 2;
    }
    const bool soft = std::strcmp(argv[1], "soft") == 0;
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    if (soft) arch.enableSoftCollisionAvoidance(SoftCollisionOptions{});
    arch.buildPlantCanopyFromLibrary(vec3(0.0f), vec2(0.3f, 0.3f), glm::ivec2(10, 10), 40.0f);
    const CollisionStats st = arch.getCollisionStats();
    // A checksum of every vertex: equal between two builds only when the plants are the same
    // to the bit (soft avoidance steers by the scene, so a changed proxy shows here).
    if (argc == 3) {
        std::uint64_t hash = 1469598103934665603ULL;  // FNV-1a
        ctx.forEachObject([&](const ObjectView& v) {
            for (const vec3& p : v.positions) {
                unsigned char bytes[sizeof p];
                std::memcpy(bytes, &p, sizeof p);
                for (unsigned char c : bytes) hash = (hash ^ c) * 1099511628211ULL;
            }
        });
        std::printf("geometry %016llx\n", static_cast<unsigned long long>(hash));
    }
    std::printf("triangles %zu cones %llu steered %llu refreshes %llu proxy_triangles %llu\n",
                ctx.triangleCount(), static_cast<unsigned long long>(st.softCones),
                static_cast<unsigned long long>(st.softSteered),
                static_cast<unsigned long long>(st.sceneRefreshes),
                static_cast<unsigned long long>(st.sceneTriangles));
    return 0;
}
