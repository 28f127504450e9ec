// glTF materials with procedural textures (MaterialStyle::Textured): a PBR material per scene
// material with its maps as embedded PNG images (material_textures.h): baseColorTexture (with
// alphaMode MASK where a leaf's outline leaves texels transparent), normalTexture,
// occlusionTexture and metallicRoughnessTexture (one ORM image), and for fruit and flowers
// their roughness. Texture files a material names (traced leaves) are embedded as before.

#include <algorithm>
#include <memory>

#include "scene_io/gltf_internal.h"
#include "scene_io/material_textures.h"

namespace plantarch::gltf {

void addTexturedMaterials(GltfArrays& d, const Scene& s, const GltfOptions& options,
                          Buffer& buffer) {
    const io::MapRequest request{
        {io::MapKind::BaseColor, io::MapKind::Normal, io::MapKind::ORM}, true, false};
    auto looks = std::make_shared<const io::MaterialLooks>(
        s.frames, options.appearance, options.includeHidden, options.uvs && options.textures,
        request);
    auto addImage = [&](const char* mimeType, std::size_t bytes, Buffer::Fill fill) {
        const int view = buffer.add(d.views, bytes, 0, std::move(fill));
        d.images.push_back({{"bufferView", view}, {"mimeType", mimeType}});
        d.textures.push_back({{"source", d.images.size() - 1}});
        return d.textures.size() - 1;
    };
    for (const EmbeddedImage& image : s.imageData)  // texture files, in Scene::images order
        addImage(image.mimeType, image.bytes.size(),
                 [&image](Sink& out) { out.write(image.bytes.data(), image.bytes.size()); });
    // The maps' textures: base colour, normal, ORM for each set of maps, in order.
    std::vector<std::array<std::size_t, 3>> mapTextures;
    for (std::size_t m = 0; m < looks->maps().size(); ++m) {
        std::array<std::size_t, 3> t{};
        for (const io::MapKind kind : request.png) {
            const std::string& png = looks->maps()[m].png[std::size_t(kind)];
            t[std::size_t(kind)] = addImage("image/png", png.size(), [looks, m, kind](Sink& out) {
                const std::string& bytes = looks->maps()[m].png[std::size_t(kind)];
                out.write(bytes.data(), bytes.size());
            });
        }
        mapTextures.push_back(t);
    }
    for (const Material& mat : s.materials) {
        const io::MaterialLook& look = looks->look(mat);
        json pbr = {{"baseColorFactor",
                     {linear(mat.color.x), linear(mat.color.y), linear(mat.color.z), 1.0}},
                    {"metallicFactor", look.factors.metallic},
                    {"roughnessFactor", look.factors.roughness}};
        json material = {{"doubleSided", true}};
        if (!mat.texture.empty() && options.textures) {
            const auto at = std::find(s.images.begin(), s.images.end(), mat.texture);
            pbr["baseColorTexture"] = {{"index", at - s.images.begin()}};
            pbr["baseColorFactor"] = {1.0, 1.0, 1.0, 1.0};
            material["alphaMode"] = "MASK";
        } else if (look.maps >= 0) {
            const auto& t = mapTextures[std::size_t(look.maps)];
            pbr["baseColorTexture"] = {{"index", t[std::size_t(io::MapKind::BaseColor)]}};
            pbr["baseColorFactor"] = {1.0, 1.0, 1.0, 1.0};
            pbr["metallicRoughnessTexture"] = {{"index", t[std::size_t(io::MapKind::ORM)]}};
            pbr["roughnessFactor"] = 1.0;
            material["normalTexture"] = {{"index", t[std::size_t(io::MapKind::Normal)]}};
            material["occlusionTexture"] = {{"index", t[std::size_t(io::MapKind::ORM)]}};
            if (looks->maps()[std::size_t(look.maps)].hasAlpha) material["alphaMode"] = "MASK";
        }
        material["pbrMetallicRoughness"] = std::move(pbr);
        material["name"] =
            !mat.name.empty() ? mat.name : std::string(io::surfaceKindName(look.kind));
        d.materials.push_back(std::move(material));
    }
}

}  // namespace plantarch::gltf
