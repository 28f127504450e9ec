// libFuzzer target: the plant structure XML reader
// (PlantArchitecture::readPlantStructureXMLString). Any input must either read or throw
// plantarch::Error; a plant that reads must write a file that reads back to the same file, and give
// a plant string that reads back (with the plant's shoot types defined) to the same string.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;

namespace {

[[noreturn]] void finding(const char* what) {
    std::fprintf(stderr, "fuzz_plant_xml: %s\n", what);
    std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string xml(reinterpret_cast<const char*>(data), size);
    Context ctx;
    PlantArchitecture arch(&ctx);
    std::vector<unsigned> ids;
    try {
        ids = arch.readPlantStructureXMLString(xml);
    } catch (const Error&) {
        if (!arch.getAllPlantIDs().empty()) finding("plants were added by a read that failed");
        return 0;
    }
    const std::string written = arch.getPlantStructureXML(ids);
    Context ctx2;
    PlantArchitecture again(&ctx2);
    std::vector<unsigned> ids2;
    try {
        ids2 = again.readPlantStructureXMLString(written);
    } catch (const Error& e) {
        std::fprintf(stderr, "%s\n", e.what());
        finding("a file written from plants that were read does not read back");
    }
    if (again.getPlantStructureXML(ids2) != written)
        finding("write -> read -> write changed the file");
    for (unsigned id : ids) {
        std::string s;
        try {
            s = arch.getPlantString(id);
        } catch (const Error&) {
            continue;  // nested too deep for a plant string
        }
        // A string names shoot types: read it where the plant's own types are defined.
        Context ctx3;
        PlantArchitecture withTypes(&ctx3);
        try {
            for (const auto& [label, params] : arch.plant(id).shootTypes)
                withTypes.defineShootType(label, params);
        } catch (const Error& e) {
            std::fprintf(stderr, "%s\n", e.what());
            finding("the shoot types of a plant that was read cannot be defined");
        }
        try {
            const unsigned q = withTypes.generatePlantFromString(s);
            if (withTypes.getPlantString(q) != s)
                finding("plant string round trip changed the string");
        } catch (const Error& e) {
            std::fprintf(stderr, "%s\n", e.what());
            finding("a plant string written from a plant does not read back");
        }
    }
    return 0;
}
