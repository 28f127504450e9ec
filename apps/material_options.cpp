// Materials of mesh and picture outputs: --materials flat|textured, --texture-size N and
// --no-texture-atlas
// (docs/formats.md, "Materials and textures").

#include <charconv>
#include <string>

#include "cli.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/OutputFormats.h"

namespace plantarch::cli {

void addMaterialOptions(CLI::App& app, GlobalOptions& global) {
    app.add_option_function<std::string>(
           "--materials",
           [&global](const std::string& text) {
               const std::optional<MaterialStyle> style = materialStyleFromName(text);
               if (!style)
                   throw Error(
                       "unknown material style",
                       {.parameter = "--materials", .value = text, .validRange = "flat, textured"});
               global.appearance.style = *style;
           },
           "Materials of .obj, .glb, .gltf, .usda, .usdz and .png outputs: flat (default: one "
           "colour per material) or textured (procedural leaf, bark and stem textures with "
           "normal and roughness maps, PBR factors for fruit and flowers)")
        ->type_name("STYLE");
    app.add_option_function<std::string>(
           "--texture-size",
           [&global](const std::string& text) {
               int size = 0;
               const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), size);
               const std::string range = "a power of two from " + std::to_string(kMinTextureSize) +
                                         " to " + std::to_string(kMaxTextureSize);
               if (ec == std::errc::result_out_of_range)
                   throw Error("texture size " + text + " is not allowed",
                               {.parameter = "--texture-size", .value = text, .validRange = range});
               if (ec != std::errc() || end != text.data() + text.size())
                   throw Error("texture size is a whole number of texels",
                               {.parameter = "--texture-size", .value = text, .validRange = range});
               MaterialOptions checked = global.appearance;
               checked.textureSize = size;
               try {
                   checkMaterialOptions(checked);
               } catch (const Error& e) {
                   throw Error(e.message(), {.parameter = "--texture-size",
                                             .value = text,
                                             .validRange = e.validRange()});
               }
               global.appearance.textureSize = size;
               if (global.textureOption.empty()) global.textureOption = "--texture-size";
           },
           "Texels a side of each texture with --materials textured: a power of two from 16 "
           "to 4096 (default 512)")
        ->type_name("N");
    app.add_flag_callback(
        "--no-texture-atlas",
        [&global] {
            global.appearance.atlas = false;
            if (global.textureOption.empty()) global.textureOption = "--no-texture-atlas";
        },
        "With --materials textured: an image per leaf material instead of one atlas of them "
        "read through texture transforms");
}

void checkMaterialOutputs(const GlobalOptions& global, const std::vector<std::string>& outputs) {
    const bool textured = global.appearance.style == MaterialStyle::Textured;
    if (!textured && !global.textureOption.empty())
        throw Error("needs textured materials",
                    {.parameter = global.textureOption, .validRange = "with --materials textured"});
    if (!textured) return;
    for (const std::string& out : outputs) {
        const std::string ext = lowerExtension(out);
        if (ext == ".obj" || ext == ".glb" || ext == ".gltf" || ext == ".usda" || ext == ".usdz" ||
            ext == ".png")
            return;
    }
    throw Error("no output holds textured materials",
                {.parameter = "--materials",
                 .value = "textured",
                 .validRange = "with an .obj, .glb, .gltf, .usda, .usdz or .png output"});
}

}  // namespace plantarch::cli
