// Textured OBJ materials: PNG maps beside the .mtl and their lines (obj_materials.h).

#include "scene_io/obj_materials.h"

#include "scene_io/export_common.h"
#include "scene_io/material_textures.h"

namespace plantarch::io {

ObjTextures::ObjTextures(const Context& context, const ObjOptions& options,
                         const std::filesystem::path& dir, const std::string& prefix,
                         std::vector<AtomicFile>& files)
    : prefix_(prefix) {
    checkMaterialOptions(options.appearance);
    if (options.appearance.style != MaterialStyle::Textured) return;
    const MapRequest request{
        {MapKind::BaseColor, MapKind::Alpha, MapKind::Normal, MapKind::Roughness}, false, false};
    const Context* contexts[] = {&context};
    looks_ = std::make_unique<MaterialLooks>(contexts, options.appearance, options.includeHidden,
                                             options.uvs, request);
    for (const MaterialMaps& maps : looks_->maps())
        for (const MapKind kind : request.png) {
            if (kind == MapKind::Alpha && !maps.hasAlpha) continue;
            files.emplace_back((dir / mapFileName(prefix_, maps, kind)).string());
            files.back().write(maps.png[std::size_t(kind)]);
            files.back().finish();
        }
}

ObjTextures::~ObjTextures() = default;

std::string ObjTextures::lines(const Material& material) const {
    if (!looks_) return "";
    const MaterialLook& look = looks_->look(material);
    char number[kMaxFloatChars];
    const auto text = [&](float v) { return std::string(number, writeFloat(number, v)); };
    std::string out =
        "Pr " + text(look.factors.roughness) + "\nPm " + text(look.factors.metallic) + "\n";
    if (look.maps < 0) return out;
    const MaterialMaps& maps = looks_->maps()[std::size_t(look.maps)];
    // A part of the atlas: the map's origin offset (-o) and its size scaled (-s) onto it.
    const std::string place =
        !look.inAtlas
            ? ""
            : "-o " + text(look.transform.offset.x) + " " + text(look.transform.offset.y) + " -s " +
                  text(look.transform.scale.x) + " " + text(look.transform.scale.y) + " ";
    const auto file = [&](MapKind kind) { return place + mapFileName(prefix_, maps, kind); };
    out += "Kd 1 1 1\nmap_Kd " + file(MapKind::BaseColor) + "\n";
    if (maps.hasAlpha) out += "map_d " + file(MapKind::Alpha) + "\n";
    out += "norm " + file(MapKind::Normal) + "\nmap_Bump " + file(MapKind::Normal) + "\nmap_Pr " +
           file(MapKind::Roughness) + "\n";
    return out;
}

}  // namespace plantarch::io
