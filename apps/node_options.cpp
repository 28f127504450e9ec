// --nodes plant|kind|organ and --instancing none|shared|gpu: how .glb, .gltf, .usda and .usdz
// outputs group each plant's geometry into nodes (docs/formats.md, "Nodes and instancing").

#include <string>

#include "cli.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/OutputFormats.h"
#include "plantarch/PlantFiles.h"

namespace plantarch::cli {

void addNodeOptions(CLI::App& app, GlobalOptions& global) {
    app.add_option_function<std::string>(
           "--nodes",
           [&global](const std::string& text) {
               const std::optional<NodeLevel> level = nodeLevelFromName(text);
               if (!level)
                   throw Error(
                       "unknown node level",
                       {.parameter = "--nodes", .value = text, .validRange = "plant, kind, organ"});
               global.nodes = *level;
           },
           "Nodes of .glb, .gltf, .usda and .usdz outputs: plant (a mesh per plant), kind "
           "(default: a mesh per organ kind under each plant) or organ (a node per shoot and "
           "per organ, named and labelled, so a viewer can pick one leaf or fruit); growth "
           "animations always have a node per organ")
        ->type_name("LEVEL");
    app.add_option_function<std::string>(
           "--instancing",
           [&global](const std::string& text) {
               const std::optional<Instancing> instancing = instancingFromName(text);
               if (!instancing)
                   throw Error("unknown instancing", {.parameter = "--instancing",
                                                      .value = text,
                                                      .validRange = "none, shared, gpu"});
               global.instancing = *instancing;
           },
           "With --nodes organ (and in animations), organs of one shape: shared (default: "
           "organ nodes that point at one mesh), gpu (one node per shape with "
           "EXT_mesh_gpu_instancing, USD point instancers; not with --frames) or none (every "
           "organ its own mesh)")
        ->type_name("MODE");
}

void checkNodeOutputs(const GlobalOptions& global, const std::vector<std::string>& outputs,
                      bool frames) {
    if (global.instancing == Instancing::Gpu && global.nodes != NodeLevel::Organ)
        throw Error("gpu instancing needs a node per organ",
                    {.parameter = "--instancing", .value = "gpu", .validRange = "--nodes organ"});
    if (global.instancing == Instancing::Gpu && frames)
        throw Error("gpu instances cannot be animated",
                    {.parameter = "--instancing",
                     .value = "gpu",
                     .validRange = "shared or none with --frames"});
    if (global.nodes == NodeLevel::Kind) return;
    if (frames && global.nodes != NodeLevel::Organ)
        throw Error("a growth animation always has a node per organ",
                    {.parameter = "--nodes",
                     .value = nodeLevelName(global.nodes),
                     .validRange = "organ, or no --nodes, with --frames"});
    for (const std::string& out : outputs) {
        const std::string ext = lowerExtension(out);
        if (holdsObjectIDs(out) && ext != ".glb" && ext != ".gltf" && ext != ".usda" &&
            ext != ".usdz")
            throw Error("node levels are written in glTF and USD only",
                        {.file = out,
                         .parameter = "--nodes",
                         .value = nodeLevelName(global.nodes),
                         .validRange = ".glb, .gltf, .usda, .usdz"});
    }
}

}  // namespace plantarch::cli
