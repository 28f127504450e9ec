// glTF materials with procedural textures (MaterialStyle::Textured): a PBR material per scene
// material with its maps as embedded PNG images (material_textures.h): baseColorTexture (with
// alphaMode MASK where a leaf's outline leaves texels transparent), normalTexture,
// occlusionTexture and metallicRoughnessTexture (one ORM image), and for fruit and flowers
// their roughness. Texture files a material names (traced leaves) are embedded as before.
// Materials whose maps are part of the atlas read them through KHR_texture_transform.

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>

#include "scene_io/export_common.h"
#include "scene_io/gltf_internal.h"
#include "scene_io/material_textures.h"

namespace plantarch::gltf {

// Per-vertex tangents (xyz along increasing u, w the bitangent's sign) of one object: the
// texture-space gradients summed over its triangles, made perpendicular to the vertex normal.
// The bitangent cross(normal, tangent) * w points toward decreasing v, the "up" of glTF's
// images, as the normal maps' green channel does (encodeMapPNG flips it for glTF).
void objectTangents(const ObjectView& o, const vec3* normals, std::vector<glm::vec4>& out) {
    std::vector<vec3> du(o.positions.size(), vec3(0.0f)), dv(o.positions.size(), vec3(0.0f));
    for (std::size_t t = 0; t + 2 < o.indices.size(); t += 3) {
        const std::uint32_t a = o.indices[t], b = o.indices[t + 1], c = o.indices[t + 2];
        const vec3 e1 = o.positions[b] - o.positions[a], e2 = o.positions[c] - o.positions[a];
        const vec2 d1 = o.uvs[b] - o.uvs[a], d2 = o.uvs[c] - o.uvs[a];
        const float det = d1.x * d2.y - d2.x * d1.y;
        if (!(std::abs(det) > 1e-12f)) continue;
        const vec3 T = (e1 * d2.y - e2 * d1.y) / det, B = (e2 * d1.x - e1 * d2.x) / det;
        if (!std::isfinite(T.x + T.y + T.z + B.x + B.y + B.z)) continue;
        for (const std::uint32_t k : {a, b, c}) {
            du[k] += T;
            dv[k] += B;
        }
    }
    out.resize(o.positions.size());
    for (std::size_t k = 0; k < out.size(); ++k) {
        const vec3 n = normals[k];
        vec3 t = du[k] - n * glm::dot(n, du[k]);
        if (!(glm::dot(t, t) > 1e-20f)) {  // no gradient: any direction across the normal
            t = std::abs(n.x) < 0.9f ? glm::cross(n, vec3(1, 0, 0)) : glm::cross(n, vec3(0, 1, 0));
        }
        t = glm::normalize(t);
        const float w = glm::dot(glm::cross(n, t), dv[k]) > 0.0f ? -1.0f : 1.0f;
        out[k] = glm::vec4(t, w);
    }
}

void addTangents(GltfArrays& d, const Scene& s, const GltfOptions& options, Buffer& buffer,
                 const Primitive& p, json& attributes) {
    if (options.appearance.style != MaterialStyle::Textured || !options.normals || !p.uvs ||
        s.normals.empty() || p.objects.empty())
        return;
    // A level of detail is written without textures, its primitives using the full level's
    // materials: there the organs that get normal maps (leaves, internodes, petioles,
    // peduncles) carry tangents too.
    const std::string_view organ = kOrganLabels[s.records[p.objects.front()].organ];
    const bool mapped = d.materials[p.material].contains("normalTexture") ||
                        (!options.textures && (organ == "leaf" || organ == "internode" ||
                                               organ == "petiole" || organ == "peduncle"));
    if (!mapped) return;
    const int view = buffer.add(d.views, p.vertices * 16, kArrayBuffer, [&s, &p](Sink& out) {
        std::vector<glm::vec4> tangents;
        for (const std::size_t i : p.objects) {
            objectTangents(s.object(i), s.normals.data() + s.normalAt[i], tangents);
            out.write(tangents.data(), tangents.size() * sizeof(glm::vec4));
        }
    });
    d.accessors.push_back(accessor(view, kFloat, p.vertices, "VEC4"));
    attributes["TANGENT"] = d.accessors.size() - 1;
}

namespace {

// KHR_texture_transform on every texture of a material that reads its part of the atlas. The
// maps' v-up transform serves as it is: glTF's images are written flipped, its UVs unchanged.
void transformTextures(json& material, const io::UVTransform& t) {
    const auto number = [](float v) {  // the float's shortest text, not its double's digits
        char text[io::kMaxFloatChars + 1] = {};
        io::writeFloat(text, v);
        return std::strtod(text, nullptr);
    };
    const json transform = {{"offset", {number(t.offset.x), number(t.offset.y)}},
                            {"scale", {number(t.scale.x), number(t.scale.y)}}};
    const auto add = [&](json& info) { info["extensions"]["KHR_texture_transform"] = transform; };
    for (const char* key : {"normalTexture", "occlusionTexture"})
        if (material.contains(key)) add(material[key]);
    json& pbr = material["pbrMetallicRoughness"];
    for (const char* key : {"baseColorTexture", "metallicRoughnessTexture"})
        if (pbr.contains(key)) add(pbr[key]);
}

}  // namespace

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
            if (options.normals)  // with tangents (addTangents, or the organ meshes')
                material["normalTexture"] = {{"index", t[std::size_t(io::MapKind::Normal)]}};
            material["occlusionTexture"] = {{"index", t[std::size_t(io::MapKind::ORM)]}};
            if (looks->maps()[std::size_t(look.maps)].hasAlpha) material["alphaMode"] = "MASK";
        }
        material["pbrMetallicRoughness"] = std::move(pbr);
        if (look.maps >= 0 && look.inAtlas) transformTextures(material, look.transform);
        material["name"] =
            !mat.name.empty() ? mat.name : std::string(io::surfaceKindName(look.kind));
        d.materials.push_back(std::move(material));
    }
}

}  // namespace plantarch::gltf
