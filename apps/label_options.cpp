// Label options of the commands that write meshes: --object-ids (object IDs in plant
// structure files and an object table next to each mesh), --ply-color and --ply-format.

#include <filesystem>

#include "cli.h"
#include "plantarch/Error.h"
#include "plantarch/PlantStructureWrite.h"

namespace plantarch::cli {

void addLabelOptions(CLI::App& app, GlobalOptions& global) {
    app.add_flag("--object-ids", global.objectIDs,
                 "Link meshes to plant files: .xml outputs hold each organ's object IDs (reading "
                 "such a file gives its objects the same IDs), and each mesh output gets an "
                 "object table, NAME.objects.json, mapping its object IDs to labels and organs");
    app.add_option_function<std::string>(
           "--ply-color",
           [&global](const std::string& text) {
               const std::optional<PlyColor> color = plyColorFromName(text);
               if (!color)
                   throw Error("unknown PLY colour",
                               {.parameter = "--ply-color",
                                .value = text,
                                .validRange = "none, organ, plant, material"});
               global.plyColor = *color;
           },
           "Vertex colours of .ply mesh outputs: none (default), organ, plant or material")
        ->type_name("MODE");
    app.add_option_function<std::string>(
           "--ply-format",
           [&global](const std::string& text) {
               if (text != "binary" && text != "ascii")
                   throw Error(
                       "unknown PLY format",
                       {.parameter = "--ply-format", .value = text, .validRange = "binary, ascii"});
               global.plyFormat =
                   text == "ascii" ? PlyFormat::Ascii : PlyFormat::BinaryLittleEndian;
           },
           "Encoding of .ply outputs: binary (default) or ascii; both hold the same labels")
        ->type_name("FORMAT");
    addSkinOptions(app, global);      // skin_options.cpp
    addLevelOptions(app, global);     // lod_options.cpp
    addMaterialOptions(app, global);  // material_options.cpp
    addNodeOptions(app, global);      // node_options.cpp
}

}  // namespace plantarch::cli
