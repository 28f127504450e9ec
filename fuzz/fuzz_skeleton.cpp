// libFuzzer target: the skeleton readers (node tables, JSON, MTG) and plants rebuilt on what
// they read. The first byte picks the format. Any input must either read or throw
// plantarch::Error (and then add no plant); a skeleton that reads must rebuild into plants or
// be refused with plantarch::Error, and a plant rebuilt must write back as a node table and
// an MTG file that read again.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/Skeleton.h"

using namespace plantarch;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    const char* formats[] = {"csv", "json", "mtg"};
    const std::string format = formats[data[0] % 3];
    const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
    Skeleton sk;
    try {
        sk = readSkeletonString(text, format, "fuzz");
    } catch (const Error&) {
        return 0;
    }
    if (sk.nodes.size() > 2000) return 0;  // keep each run short
    Context ctx;
    PlantArchitecture arch(&ctx);
    ShootParameters stem;
    stem.phytomer_parameters.leaf.leaves_per_petiole = 3;
    arch.defineShootType("stem", stem);
    ReconstructOptions o;
    o.baseShootType = "stem";
    o.branchShootType = "stem";
    o.shoot.attachTolerance = 10.0f;
    std::vector<unsigned> plants;
    try {
        plants = reconstructPlants(arch, sk, o);
    } catch (const Error&) {
        if (!arch.getAllPlantIDs().empty()) {
            std::fprintf(stderr, "fuzz_skeleton: a refused skeleton left plants behind\n");
            std::abort();
        }
        return 0;
    }
    try {
        readSkeletonString(skeletonCSV(plantSkeleton(arch, plants)), "csv", "again");
        readSkeletonString(plantsMTG(arch, plants), "mtg", "again");
    } catch (const Error& e) {
        std::fprintf(stderr, "fuzz_skeleton: a rebuilt plant's files do not read: %s\n", e.what());
        std::abort();
    }
    return 0;
}
