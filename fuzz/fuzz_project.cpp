// libFuzzer target: the project file reader (readProjectString) and its checks
// (checkProject). Any input must either read or throw plantarch::Error with one line (of at
// most 2,000 bytes; any other exception is a crash); a project that
// reads must write text that reads back to the same text, and its checks either pass or throw
// plantarch::Error the same way.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "plantarch/Error.h"
#include "plantarch/Project.h"

using namespace plantarch;

namespace {

// Relative paths of a fuzzed project are taken from a folder that does not exist.
const char* kFolder = "/nonexistent/plantarch-fuzz-project";

void requireOneLine(const Error& e, const char* stage) {
    const std::string what = e.what();
    // (Anything thrown but a plantarch::Error, such as the JSON library's exceptions, leaves
    // this function: libFuzzer reports it as a crash.)
    const bool bad = what.find('\n') != std::string::npos || what.find('\r') != std::string::npos ||
                     what.size() > 2000;
    if (bad) {
        std::fprintf(stderr, "fuzz_project: %s: not a one-line error (%zu bytes): %s\n", stage,
                     what.size(), what.c_str());
        std::abort();
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    Project project;
    try {
        project = readProjectString(text, "fuzz.json", kFolder);
    } catch (const Error& e) {
        requireOneLine(e, "read");
        return 0;
    }
    const std::string written = writeProjectString(project);
    try {
        const Project again = readProjectString(written, "written.json", kFolder);
        if (writeProjectString(again) != written) {
            std::fprintf(stderr, "fuzz_project: write -> read -> write changed the file\n");
            std::abort();
        }
    } catch (const Error& e) {
        std::fprintf(stderr, "fuzz_project: written file does not read back: %s\n%s\n", e.what(),
                     written.c_str());
        std::abort();
    }
    try {
        checkProject(project);
    } catch (const Error& e) {
        requireOneLine(e, "check");
    }
    return 0;
}
