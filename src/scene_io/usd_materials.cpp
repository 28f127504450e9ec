// USD materials and the .usdz package (usd_materials.h).

#include "scene_io/usd_materials.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstring>

#include "plantarch/Error.h"
#include "scene_io/export_common.h"
#include "scene_io/material_textures.h"

namespace plantarch::io {

namespace usdmat {

std::string floatText(float v) {
    char number[kMaxFloatChars];
    return std::string(number, writeFloat(number, v));
}

std::string identifier(const std::string& text) {
    std::string out;
    for (char c : text) out += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
    if (out.empty() || std::isdigit(static_cast<unsigned char>(out[0]))) out = "_" + out;
    return out;
}

std::uint32_t usdzCrc32(std::string_view bytes) {
    static const auto table = [] {
        std::array<std::uint32_t, 256> t{};
        for (std::uint32_t i = 0; i < 256; ++i) {
            std::uint32_t c = i;
            for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
            t[i] = c;
        }
        return t;
    }();
    std::uint32_t c = 0xFFFFFFFFu;
    for (unsigned char b : bytes) c = table[(c ^ b) & 0xFF] ^ (c >> 8);
    return c ^ 0xFFFFFFFFu;
}

void le16(std::string& s, std::uint32_t v) {
    s += char(v & 0xFF);
    s += char((v >> 8) & 0xFF);
}
void le32(std::string& s, std::uint32_t v) {
    le16(s, v & 0xFFFF);
    le16(s, v >> 16);
}

}  // namespace usdmat

UsdLooks::UsdLooks(std::span<const Context* const> contexts, const UsdOptions& options,
                   const std::string& prefix)
    : prefix_(prefix) {
    checkMaterialOptions(options.appearance);
    if (options.appearance.style != MaterialStyle::Textured) return;
    const MapRequest request{{MapKind::BaseColor, MapKind::Normal, MapKind::ORM}, false, false};
    looks_ = std::make_unique<MaterialLooks>(contexts, options.appearance, options.includeHidden,
                                             options.uvs, request);
    for (const Context* ctx : contexts)
        for (const ObjectID id : exportedObjects(*ctx, options.includeHidden)) {
            const Material& m = ctx->material(ctx->objectMaterial(id));
            if (std::find(materials_.begin(), materials_.end(), m) == materials_.end())
                materials_.push_back(m);
        }
}

UsdLooks::~UsdLooks() = default;

std::vector<std::pair<std::string, std::string_view>> UsdLooks::files() const {
    std::vector<std::pair<std::string, std::string_view>> out;
    if (!looks_) return out;
    for (const MaterialMaps& maps : looks_->maps())
        for (const MapKind kind : {MapKind::BaseColor, MapKind::Normal, MapKind::ORM})
            out.emplace_back(mapFileName(prefix_, maps, kind), maps.png[std::size_t(kind)]);
    return out;
}

std::string UsdLooks::scope() const {
    using usdmat::floatText;
    if (!looks_) return "";
    std::string s = "    def Scope \"Looks\"\n    {\n";
    for (std::size_t i = 0; i < materials_.size(); ++i) {
        const Material& mat = materials_[i];
        const MaterialLook& look = looks_->look(mat);
        const std::string name = usdmat::identifier(
            (mat.name.empty() ? std::string(surfaceKindName(look.kind)) : mat.name) + "_" +
            std::to_string(i));
        const std::string path = "</plantarch/Looks/" + name;
        s += "        def Material \"" + name + "\"\n        {\n";
        s += "            token outputs:surface.connect = " + path + "/Surface.outputs:surface>\n";
        s += "\n            def Shader \"Surface\"\n            {\n"
             "                uniform token info:id = \"UsdPreviewSurface\"\n";
        const MaterialMaps* maps =
            look.maps >= 0 ? &looks_->maps()[std::size_t(look.maps)] : nullptr;
        if (maps) {
            s += "                color3f inputs:diffuseColor.connect = " + path +
                 "/BaseColor.outputs:rgb>\n";
            if (maps->hasAlpha)
                s += "                float inputs:opacity.connect = " + path +
                     "/BaseColor.outputs:a>\n"
                     "                float inputs:opacityThreshold = 0.5\n";
            s += "                float inputs:roughness.connect = " + path + "/ORM.outputs:g>\n";
            s += "                float inputs:occlusion.connect = " + path + "/ORM.outputs:r>\n";
            s += "                normal3f inputs:normal.connect = " + path +
                 "/Normal.outputs:rgb>\n";
        } else {
            const vec3 c = glm::clamp(mat.color, vec3(0.0f), vec3(1.0f));
            s += "                color3f inputs:diffuseColor = (" + floatText(c.r) + ", " +
                 floatText(c.g) + ", " + floatText(c.b) + ")\n";
            s += "                float inputs:roughness = " + floatText(look.factors.roughness) +
                 "\n";
        }
        s += "                float inputs:metallic = " + floatText(look.factors.metallic) +
             "\n                token outputs:surface\n            }\n";
        if (maps) {
            s += "\n            def Shader \"TexCoord\"\n            {\n"
                 "                uniform token info:id = \"UsdPrimvarReader_float2\"\n"
                 "                string inputs:varname = \"st\"\n"
                 "                float2 outputs:result\n            }\n";
            // A part of the atlas: its coordinates through a UsdTransform2d (scale, then
            // translation), which the textures read instead of the primvar.
            std::string st = "/TexCoord.outputs:result>";
            if (look.inAtlas) {
                const UVTransform& t = look.transform;
                s += "\n            def Shader \"Transform\"\n            {\n"
                     "                uniform token info:id = \"UsdTransform2d\"\n"
                     "                float2 inputs:in.connect = " +
                     path + st + "\n                float2 inputs:scale = (" +
                     floatText(t.scale.x) + ", " + floatText(t.scale.y) +
                     ")\n                float2 inputs:translation = (" + floatText(t.offset.x) +
                     ", " + floatText(t.offset.y) +
                     ")\n                float2 outputs:result\n            }\n";
                st = "/Transform.outputs:result>";
            }
            const auto texture = [&](const char* shader, MapKind kind, bool srgb,
                                     const char* outputs) {
                s += std::string("\n            def Shader \"") + shader +
                     "\"\n            {\n"
                     "                uniform token info:id = \"UsdUVTexture\"\n"
                     "                asset inputs:file = @./" +
                     mapFileName(prefix_, *maps, kind) +
                     "@\n"
                     "                float2 inputs:st.connect = " +
                     path + st +
                     "\n"
                     "                token inputs:wrapS = \"repeat\"\n"
                     "                token inputs:wrapT = \"repeat\"\n"
                     "                token inputs:sourceColorSpace = \"" +
                     (srgb ? "sRGB" : "raw") + "\"\n";
                if (kind == MapKind::Normal)
                    s += "                float4 inputs:scale = (2, 2, 2, 1)\n"
                         "                float4 inputs:bias = (-1, -1, -1, 0)\n";
                s += std::string(outputs) + "            }\n";
            };
            texture("BaseColor", MapKind::BaseColor, true,
                    "                float3 outputs:rgb\n                float outputs:a\n");
            texture("Normal", MapKind::Normal, false, "                float3 outputs:rgb\n");
            texture("ORM", MapKind::ORM, false,
                    "                float outputs:r\n                float outputs:g\n");
        }
        s += "        }\n";
    }
    return s + "    }\n";
}

std::string UsdLooks::subsets(const Context& context, std::span<const ObjectID> objects) const {
    if (!looks_) return "";
    std::vector<std::vector<std::size_t>> faces(materials_.size());
    std::size_t face = 0;
    for (const ObjectID id : objects) {
        const Material& m = context.material(context.objectMaterial(id));
        const auto at = std::find(materials_.begin(), materials_.end(), m);
        const std::size_t n = context.object(id).triangleCount();
        std::vector<std::size_t>& list = faces[std::size_t(at - materials_.begin())];
        for (std::size_t t = 0; t < n; ++t) list.push_back(face + t);
        face += n;
    }
    std::string s =
        "            uniform token subsetFamily:materialBind:familyType = "
        "\"partition\"\n";
    for (std::size_t i = 0; i < materials_.size(); ++i) {
        if (faces[i].empty()) continue;
        const Material& mat = materials_[i];
        const std::string name = usdmat::identifier(
            (mat.name.empty() ? std::string(surfaceKindName(looks_->look(mat).kind)) : mat.name) +
            "_" + std::to_string(i));
        s += "\n            def GeomSubset \"" + name +
             "\" (\n                prepend apiSchemas = [\"MaterialBindingAPI\"]\n"
             "            )\n            {\n"
             "                uniform token elementType = \"face\"\n"
             "                uniform token familyName = \"materialBind\"\n"
             "                int[] indices = [";
        for (std::size_t k = 0; k < faces[i].size(); ++k) {
            if (k) s += ", ";
            s += std::to_string(faces[i][k]);
        }
        s += "]\n                rel material:binding = </plantarch/Looks/" + name + ">\n";
        s += "            }\n";
    }
    return s;
}

void writeUsdz(AtomicFile& out, std::span<const std::pair<std::string, std::string_view>> files) {
    using usdmat::le16;
    using usdmat::le32;
    std::string directory;
    std::uint64_t offset = 0;
    for (const auto& [name, data] : files) {
        const std::uint32_t crc = usdmat::usdzCrc32(data);
        // The data starts after the 30-byte header, the name and an extra field that pads it
        // to a multiple of 64 (an extra field needs at least its 4-byte header).
        std::size_t pad = (64 - (offset + 30 + name.size() + 4) % 64) % 64;
        std::string local;
        le32(local, 0x04034b50u);
        le16(local, 20);    // version needed
        le16(local, 0);     // flags
        le16(local, 0);     // stored
        le16(local, 0);     // time
        le16(local, 0x21);  // date: 1980-01-01
        le32(local, crc);
        le32(local, std::uint32_t(data.size()));
        le32(local, std::uint32_t(data.size()));
        le16(local, std::uint32_t(name.size()));
        le16(local, std::uint32_t(4 + pad));
        local += name;
        le16(local, 0x1986);  // an unregistered extra field id: padding
        le16(local, std::uint32_t(pad));
        local.append(pad, '\0');
        if (offset + local.size() + data.size() >= 0xFFFFFFFFull)
            throw Error("a USDZ package of more than 4 GB is not written",
                        {.file = out.path(), .validRange = "up to 4 GB"});
        out.write(local);
        out.write(data.data(), data.size());
        std::string entry;
        le32(entry, 0x02014b50u);
        le16(entry, 20);
        le16(entry, 20);
        le16(entry, 0);
        le16(entry, 0);
        le16(entry, 0);
        le16(entry, 0x21);
        le32(entry, crc);
        le32(entry, std::uint32_t(data.size()));
        le32(entry, std::uint32_t(data.size()));
        le16(entry, std::uint32_t(name.size()));
        le16(entry, 0);  // extra
        le16(entry, 0);  // comment
        le16(entry, 0);  // disk
        le16(entry, 0);  // internal attributes
        le32(entry, 0);  // external attributes
        le32(entry, std::uint32_t(offset));
        entry += name;
        directory += entry;
        offset += local.size() + data.size();
    }
    std::string end;
    le32(end, 0x06054b50u);
    le16(end, 0);
    le16(end, 0);
    le16(end, std::uint32_t(files.size()));
    le16(end, std::uint32_t(files.size()));
    le32(end, std::uint32_t(directory.size()));
    le32(end, std::uint32_t(offset));
    le16(end, 0);
    out.write(directory);
    out.write(end);
}

}  // namespace plantarch::io
