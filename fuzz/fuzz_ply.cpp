// libFuzzer target: the PLY reader (readPLY, with the labels writePLY writes). Any input must
// either read or throw plantarch::Error and leave the Context empty; a PLY that reads must
// write a PLY (binary, and ASCII) that reads back to the same objects, triangles and labels.

#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_mesh.h"
#include "plantarch/Context.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"

using namespace plantarch;

namespace {

[[noreturn]] void fail(const std::string& why) {
    fuzz::fail("ply", why);
}

std::string summary(const Context& ctx) {
    return fuzz::summary(ctx, [](const std::string&, ObjectID) { return true; });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const std::string input = fuzz::scratch("ply", "in.ply"),
                             output = fuzz::scratch("ply", "out.ply");
    fuzz::writeInput(input, data, size);
    Context ctx;
    try {
        readPLY(ctx, input);
    } catch (const Error&) {
        if (ctx.objectCount() != 0) fail("a failed read left objects in the Context");
        return 0;
    }
    for (PlyFormat format : {PlyFormat::BinaryLittleEndian, PlyFormat::Ascii}) {
        try {
            PlyOptions options;
            options.format = format;
            writePLY(ctx, output, options);
            Context again;
            readPLY(again, output);
            if (summary(again) != summary(ctx))
                fail("write -> read changed the objects or labels:\n" + summary(ctx) +
                     "-- became --\n" + summary(again));
        } catch (const Error& e) {
            fail(std::string("a written PLY does not read back: ") + e.what());
        }
    }
    return 0;
}
