// libFuzzer target: the species file reader (readSpeciesString). Any input must either read
// or throw plantarch::Error; a species that reads must write a file that reads back to the
// same file.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "plantarch/Error.h"
#include "plantarch/SpeciesIO.h"

using namespace plantarch;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string xml(reinterpret_cast<const char*>(data), size);
    SpeciesModel model;
    try {
        model = readSpeciesString(xml, "fuzz.xml");
    } catch (const Error&) {
        return 0;
    }
    const std::string written = writeSpeciesString(model);
    try {
        const SpeciesModel again = readSpeciesString(written, "written.xml");
        if (writeSpeciesString(again) != written) {
            std::fprintf(stderr, "fuzz_species: write -> read -> write changed the file\n");
            std::abort();
        }
    } catch (const Error& e) {
        std::fprintf(stderr, "fuzz_species: written file does not read back: %s\n", e.what());
        std::abort();
    }
    return 0;
}
