// Levels of detail and compression of glTF outputs: --lod LEVELS and --meshopt
// (docs/formats.md, "Levels of detail").

#include "cli.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/OutputFormats.h"
#include "plantarch/PlantFiles.h"

namespace plantarch::cli {

void addLevelOptions(CLI::App& app, GlobalOptions& global) {
    app.add_option_function<std::string>(
           "--lod",
           [&global](const std::string& text) { global.levels = parseGltfLevels(text, "--lod"); },
           "Levels of detail of .glb/.gltf outputs after the full one, as MSFT_lod: "
           "comma-separated reduced (a quarter of each organ's triangles), reduced:SHARE or "
           "cards (a quad or two per organ), each optionally @COVERAGE (the screen share "
           "below which it shows), e.g. reduced,cards")
        ->type_name("LEVELS");
    app.add_flag("--meshopt", global.meshopt,
                 "Compress .glb/.gltf outputs with EXT_meshopt_compression (lossless; read by "
                 "three.js with its MeshoptDecoder, Babylon.js; not by Blender 3.4)");
}

void checkLevelOutputs(const GlobalOptions& global, const std::vector<std::string>& outputs,
                       bool frames) {
    if (global.levels.empty() && !global.meshopt) return;
    const char* option = global.levels.empty() ? "--meshopt" : "--lod";
    if (frames)
        throw Error("levels of detail and meshopt compression are not written with --frames",
                    {.parameter = option, .validRange = "without --frames"});
    for (const std::string& out : outputs) {
        const std::string ext = lowerExtension(out);
        if (holdsObjectIDs(out) && ext != ".glb" && ext != ".gltf")
            throw Error("levels of detail and meshopt compression are written in glTF only",
                        {.file = out, .parameter = option, .validRange = ".glb, .gltf"});
    }
}

}  // namespace plantarch::cli
