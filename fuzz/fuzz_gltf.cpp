// libFuzzer target: the glTF reader (readGLTF: .glb, and .gltf with embedded buffers; an input
// that starts with the binary magic "glTF" is read as .glb, any other as .gltf). Any input
// must either read or throw plantarch::Error and leave the Context empty; a scene that reads
// must write a .glb that reads back to the same objects, triangles and labels.

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

#include "fuzz_mesh.h"
#include "plantarch/Context.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"

using namespace plantarch;

namespace {

[[noreturn]] void fail(const std::string& why) {
    fuzz::fail("gltf", why);
}

std::string summary(const Context& ctx) {
    return fuzz::summary(ctx, [](const std::string&, ObjectID) { return true; });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const std::string binary = fuzz::scratch("gltf", "in.glb"),
                             text = fuzz::scratch("gltf", "in.gltf"),
                             output = fuzz::scratch("gltf", "out.glb");
    const bool glb = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
    const std::string& input = glb ? binary : text;
    fuzz::writeInput(input, data, size);
    Context ctx;
    try {
        readGLTF(ctx, input);
    } catch (const Error&) {
        if (ctx.objectCount() != 0) fail("a failed read left objects in the Context");
        return 0;
    }
    try {
        writeGLTF(ctx, output);
        Context again;
        readGLTF(again, output);
        if (summary(again) != summary(ctx))
            fail("write -> read changed the objects or labels:\n" + summary(ctx) +
                 "-- became --\n" + summary(again));
    } catch (const Error& e) {
        fail(std::string("a written .glb does not read back: ") + e.what());
    }
    return 0;
}
