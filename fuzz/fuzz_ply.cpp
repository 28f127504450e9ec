// libFuzzer target: the PLY reader (readPLY, with the labels writePLY writes). Any input must
// either read or throw plantarch::Error and leave the Context empty; a PLY that reads must
// write a PLY (binary, and ASCII) that reads back to the same objects, triangles and labels.

#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_mesh.h"
#include "plantarch/Context.h"
#include "plantarch/Export.h"

using namespace plantarch;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const std::string input = fuzz::scratch("ply", "in.ply"),
                             output = fuzz::scratch("ply", "out.ply");
    fuzz::writeInput(input, data, size);
    Context ctx;
    if (!fuzz::readsOrAddsNothing("ply", ctx, [&](Context& c) { readPLY(c, input); })) return 0;
    for (PlyFormat format : {PlyFormat::BinaryLittleEndian, PlyFormat::Ascii}) {
        PlyOptions options;
        options.format = format;
        fuzz::roundTrips(
            "ply", "PLY", ctx, [&](const Context& c) { writePLY(c, output, options); },
            [&](Context& c) { readPLY(c, output); });
    }
    return 0;
}
