// libFuzzer target: the OBJ reader (readOBJ, with plantarch's label comments). Any input must
// either read or throw plantarch::Error and leave the Context empty; an OBJ that reads must
// write an OBJ that reads back to the same objects, triangles and labels.

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
    fuzz::fail("obj", why);
}

// An object without a name gets the name its `o` line gives it when read back, so "name"
// counts only where `named` has one.
std::string summary(const Context& ctx, const Context& named) {
    return fuzz::summary(ctx, [&](const std::string& label, ObjectID id) {
        return label != "name" || (named.doesObjectExist(id) && named.hasObjectData(id, "name"));
    });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const std::string input = fuzz::scratch("obj", "in.obj"),
                             output = fuzz::scratch("obj", "out.obj");
    fuzz::writeInput(input, data, size);
    // Kept recorded IDs may leave up to a million unused below them, which a Context pays
    // for in records; a small limit takes the same path at a thousandth of the cost per run.
    ObjReadOptions reading;
    reading.maxSkippedObjectIDs = 1000;
    Context ctx;
    try {
        readOBJ(ctx, input, reading);
    } catch (const Error&) {
        if (ctx.objectCount() != 0) fail("a failed read left objects in the Context");
        return 0;
    }
    try {
        ObjOptions options;
        options.materials = false;
        writeOBJ(ctx, output, options);
        Context again;
        readOBJ(again, output, reading);
        if (summary(again, ctx) != summary(ctx, ctx))
            fail("write -> read changed the objects or labels:\n" + summary(ctx, ctx) +
                 "-- became --\n" + summary(again, ctx));
    } catch (const Error& e) {
        fail(std::string("a written OBJ does not read back: ") + e.what());
    }
    return 0;
}
