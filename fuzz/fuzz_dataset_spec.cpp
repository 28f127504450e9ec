// libFuzzer target: the dataset spec reader (readDatasetSpecString) and the drawing of samples
// (drawDatasetSample). Any input must either read or throw plantarch::Error with one line (of
// at most 2,000 bytes; any other exception is a crash); a spec that reads must draw its first
// samples without an error, the same twice, each a project whose text reads back to itself.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "plantarch/Dataset.h"
#include "plantarch/Error.h"

using namespace plantarch;

namespace {

const char* kFolder = "/nonexistent/plantarch-fuzz-dataset";

[[noreturn]] void fail(const char* what, const std::string& detail) {
    std::fprintf(stderr, "fuzz_dataset_spec: %s: %s\n", what, detail.c_str());
    std::abort();
}

void requireOneLine(const Error& e, const char* stage) {
    const std::string what = e.what();
    if (what.find('\n') != std::string::npos || what.find('\r') != std::string::npos ||
        what.size() > 2000)
        fail(stage, "not a one-line error: " + what);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    DatasetSpec spec;
    try {
        spec = readDatasetSpecString(text, "fuzz.json", kFolder);
    } catch (const Error& e) {
        requireOneLine(e, "read");
        return 0;
    }
    for (std::size_t i = 0; i < 3; ++i) {
        try {
            const DatasetSample a = drawDatasetSample(spec, i);
            const DatasetSample b = drawDatasetSample(spec, i);
            const std::string project = writeProjectString(a.project);
            if (project != writeProjectString(b.project) || a.split != b.split)
                fail("draw", "sample " + std::to_string(i) + " drawn twice differs");
            const Project again = readProjectString(project, "drawn.json", kFolder);
            if (writeProjectString(again) != project)
                fail("draw", "a drawn project does not read back to itself:\n" + project);
        } catch (const Error& e) {
            fail("draw", std::string("a spec that reads cannot draw a sample: ") + e.what());
        }
    }
    return 0;
}
