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
#include "plantarch/Export.h"

using namespace plantarch;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const std::string binary = fuzz::scratch("gltf", "in.glb"),
                             text = fuzz::scratch("gltf", "in.gltf"),
                             output = fuzz::scratch("gltf", "out.glb");
    const bool glb = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
    const std::string& input = glb ? binary : text;
    fuzz::writeInput(input, data, size);
    Context ctx;
    if (!fuzz::readsOrAddsNothing("gltf", ctx, [&](Context& c) { readGLTF(c, input); })) return 0;
    fuzz::roundTrips(
        "gltf", ".glb", ctx, [&](const Context& c) { writeGLTF(c, output); },
        [&](Context& c) { readGLTF(c, output); });
    return 0;
}
