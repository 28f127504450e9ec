// libFuzzer target: the plant string reader (PlantArchitecture::generatePlantFromString).
// Any input must either read or throw plantarch::Error; the string of a plant read from a
// string must read back to the same string.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    Context ctx;
    PlantArchitecture arch(&ctx);
    ShootParameters compound;
    compound.phytomer_parameters.leaf.leaves_per_petiole = 3;
    compound.phytomer_parameters.inflorescence.unique_prototypes = 3;
    arch.defineShootType("stem", ShootParameters{});
    arch.defineShootType("leafy", compound);
    unsigned id = 0;
    try {
        id = arch.generatePlantFromString(text);
    } catch (const Error&) {
        if (!arch.getAllPlantIDs().empty()) std::abort();
        return 0;
    }
    for (int digits : {0, 4}) {
        PlantStringOptions o;
        o.significantDigits = digits;
        const std::string s = arch.getPlantString(id, o);
        try {
            const unsigned q = arch.generatePlantFromString(s);
            if (arch.getPlantString(q, o) != s) {
                std::fprintf(stderr, "fuzz_plant_string: round trip changed the string\n");
                std::abort();
            }
        } catch (const Error& e) {
            std::fprintf(stderr, "fuzz_plant_string: %s\n", e.what());
            std::abort();
        }
    }
    return 0;
}
