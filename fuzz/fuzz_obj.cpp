// libFuzzer target: the OBJ reader (readOBJ, with plantarch's label comments). Any input must
// either read or throw plantarch::Error and leave the Context empty; an OBJ that reads must
// write an OBJ that reads back to the same objects, triangles and labels.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <type_traits>
#include <variant>

#include "plantarch/Context.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"

using namespace plantarch;

namespace {

// A file of this process's own on a memory file system when there is one.
std::string scratch(const char* name) {
    const char* dir = ::access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
    return std::string(dir) + "/plantarch-fuzz-obj-" + std::to_string(::getpid()) + "-" + name;
}

[[noreturn]] void fail(const std::string& why) {
    std::fprintf(stderr, "fuzz_obj: %s\n", why.c_str());
    std::abort();
}

// Objects, triangles and every object's labels, as text. An object without a name gets the
// name its `o` line gives it when read back, so "name" counts only where `named` has one.
std::string summary(const Context& ctx, const Context& named) {
    std::string s = std::to_string(ctx.objectCount()) + " objects, " +
                    std::to_string(ctx.triangleCount()) + " triangles\n";
    for (ObjectID id : ctx.objectIDs())
        for (const std::string& label : ctx.objectDataLabels())
            if (auto v = ctx.objectData(id, label);
                v &&
                (label != "name" || (named.doesObjectExist(id) && named.hasObjectData(id, "name"))))
                std::visit(
                    [&](const auto& x) {
                        using T = std::decay_t<decltype(x)>;
                        s += label + "=";
                        if constexpr (std::is_same_v<T, std::string>)
                            s += x;
                        else if constexpr (std::is_same_v<T, vec3>)
                            s += std::to_string(x.x) + "," + std::to_string(x.y) + "," +
                                 std::to_string(x.z);
                        else
                            s += std::to_string(x);
                        s += ";";
                    },
                    *v);
    return s;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const std::string input = scratch("in.obj"), output = scratch("out.obj");
    {
        std::ofstream out(input, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
    }
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
