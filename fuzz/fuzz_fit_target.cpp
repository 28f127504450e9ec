// libFuzzer target: the fit target reader (readFitTargetString) and its checks against a
// species (checkFitTarget, on a bean read once). Any input must either read or throw
// plantarch::Error with one line (of at most 2,000 bytes; any other exception is a crash).

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "plantarch/Calibration.h"
#include "plantarch/Error.h"
#include "plantarch/SpeciesIO.h"

using namespace plantarch;

namespace {

// Relative point cloud files of a fuzzed target are taken from a folder that does not exist.
const char* kFolder = "/nonexistent/plantarch-fuzz-fit";

void requireOneLine(const Error& e, const char* stage) {
    const std::string what = e.what();
    const bool bad = what.find('\n') != std::string::npos || what.find('\r') != std::string::npos ||
                     what.size() > 2000;
    if (bad) {
        std::fprintf(stderr, "fuzz_fit_target: %s: not a one-line error (%zu bytes): %s\n", stage,
                     what.size(), what.c_str());
        std::abort();
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const SpeciesModel bean = loadSpecies("bean");
    const std::string text(reinterpret_cast<const char*>(data), size);
    FitTarget target;
    try {
        target = readFitTargetString(text, "fuzz.json", kFolder);
    } catch (const Error& e) {
        requireOneLine(e, "read");
        return 0;
    }
    try {
        checkFitTarget(bean, target);
    } catch (const Error& e) {
        requireOneLine(e, "check");
    }
    return 0;
}
