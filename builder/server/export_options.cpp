// An export's variant from a request (export_options.h): each field read as text (JSON types
// checked first), checked with the command line's checks (material style, texture size, node
// level, levels of detail), then checked against the format and against each other as the
// writers would refuse them, before any work.

#include "builder/server/export_options.h"

#include <charconv>
#include <cmath>
#include <map>
#include <optional>

#include "plantarch/Error.h"
#include "plantarch/Export.h"

namespace plantarch::builder {

namespace {

// The variant's fields as text, absent where the request does not give them.
using Texts = std::map<std::string, std::string>;

bool isFlag(const std::string& field) {
    return field == "atlas" || field == "meshopt" || field == "skin";
}

bool flag(const std::string& field, const std::string& text) {
    if (text == "true" || text == "1") return true;
    if (text == "false" || text == "0") return false;
    throw Error("not true or false",
                {.parameter = field, .value = text, .validRange = "true, false"});
}

int textureSize(const std::string& text) {
    const std::string range = "a power of two from " + std::to_string(kMinTextureSize) + " to " +
                              std::to_string(kMaxTextureSize);
    int size = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), size);
    if (ec == std::errc::result_out_of_range)
        throw Error("texture size " + text + " is not allowed",
                    {.parameter = "texture_size", .value = text, .validRange = range});
    if (ec != std::errc() || end != text.data() + text.size())
        throw Error("texture size is a whole number of texels",
                    {.parameter = "texture_size", .value = text, .validRange = range});
    checkMaterialOptions({.textureSize = size});  // names texture_size
    return size;
}

bool isMesh(const std::string& format) {
    return format == "obj" || format == "ply" || format == "glb" || format == "gltf" ||
           format == "usda";
}

PlantFileOptions variant(const Texts& t, const std::string& format) {
    for (const auto& [field, text] : t)
        if (text.size() > 80)
            throw Error("too long", {.parameter = field,
                                     .value = clip(text, 40),
                                     .validRange = "at most 80 characters"});
    PlantFileOptions o;
    auto given = [&](const char* field) { return t.count(field) > 0; };
    if (given("materials")) {
        const std::optional<MaterialStyle> style = materialStyleFromName(t.at("materials"));
        if (!style)
            throw Error("unknown material style", {.parameter = "materials",
                                                   .value = t.at("materials"),
                                                   .validRange = "flat, textured"});
        o.appearance.style = *style;
    }
    if (given("texture_size")) o.appearance.textureSize = textureSize(t.at("texture_size"));
    if (given("atlas")) o.appearance.atlas = flag("atlas", t.at("atlas"));  // --no-texture-atlas
    if (given("nodes")) {
        const std::optional<NodeLevel> level = nodeLevelFromName(t.at("nodes"));
        if (!level)
            throw Error(
                "unknown node level",
                {.parameter = "nodes", .value = t.at("nodes"), .validRange = "plant, kind, organ"});
        o.nodes = *level;
    }
    if (given("instancing")) {
        const std::optional<Instancing> instancing = instancingFromName(t.at("instancing"));
        if (!instancing)
            throw Error("unknown instancing", {.parameter = "instancing",
                                               .value = t.at("instancing"),
                                               .validRange = "none, shared, gpu"});
        o.instancing = *instancing;
    }
    if (given("lod")) o.levels = parseGltfLevels(t.at("lod"), "lod");
    if (given("meshopt")) o.meshoptCompression = flag("meshopt", t.at("meshopt"));
    if (given("skin")) o.skin = flag("skin", t.at("skin"));

    // What the format holds, and the combinations the writers refuse.
    const bool gltf = format == "glb" || format == "gltf";
    const std::string lod = given("lod") ? t.at("lod") : "";
    if (o.appearance.style == MaterialStyle::Textured && (!isMesh(format) || format == "ply"))
        throw Error("textured materials are written in OBJ, glTF and USD only",
                    {.parameter = "materials",
                     .value = "textured",
                     .validRange = "format obj, glb, gltf or usda"});
    if (o.nodes != NodeLevel::Kind && !gltf && format != "usda")
        throw Error("node levels are written in glTF and USD only",
                    {.parameter = "nodes",
                     .value = nodeLevelName(o.nodes),
                     .validRange = "format glb, gltf or usda"});
    if (!o.levels.empty() && !gltf)
        throw Error("levels of detail are written in glTF only",
                    {.parameter = "lod", .value = lod, .validRange = "format glb or gltf"});
    if (o.meshoptCompression && !gltf)
        throw Error("meshopt compression is written in glTF only",
                    {.parameter = "meshopt", .value = "true", .validRange = "format glb or gltf"});
    if (o.skin && !gltf && format != "usda")
        throw Error(
            "skins are written in glTF and USD only",
            {.parameter = "skin", .value = "true", .validRange = "format glb, gltf or usda"});
    if (o.instancing == Instancing::Gpu && o.nodes != NodeLevel::Organ)
        throw Error("gpu instancing needs a node per organ",
                    {.parameter = "instancing", .value = "gpu", .validRange = "nodes = organ"});
    if (o.nodes == NodeLevel::Organ && !o.levels.empty())
        throw Error("a node per organ cannot be written with levels of detail",
                    {.parameter = "lod", .value = lod, .validRange = "none with nodes = organ"});
    if (o.nodes == NodeLevel::Organ && o.skin)
        throw Error(
            "a node per organ cannot be written with a skin",
            {.parameter = "skin", .value = "true", .validRange = "false with nodes = organ"});
    if (o.skin && !o.levels.empty())
        throw Error("levels of detail are not written with skins",
                    {.parameter = "lod", .value = lod, .validRange = "none with skin = true"});
    return o;
}

}  // namespace

const std::vector<std::string>& exportVariantFields() {
    static const std::vector<std::string> fields = {
        "materials", "texture_size", "atlas", "nodes", "instancing", "lod", "meshopt", "skin"};
    return fields;
}

PlantFileOptions exportVariant(const json& body, const std::string& format) {
    Texts texts;
    for (const std::string& field : exportVariantFields()) {
        if (!body.contains(field) || body[field].is_null()) continue;
        const json& v = body[field];
        if (isFlag(field)) {
            if (!v.is_boolean())
                throw Error(
                    "expected true or false",
                    {.parameter = field, .value = shownJSON(v), .validRange = "true, false"});
            texts[field] = v.get<bool>() ? "true" : "false";
        } else if (field == "texture_size") {
            const std::string range = "a power of two from " + std::to_string(kMinTextureSize) +
                                      " to " + std::to_string(kMaxTextureSize);
            if (v.is_number_integer())
                texts[field] = v.dump();
            else if (v.is_number_float() && std::isfinite(v.get<double>()) &&
                     v.get<double>() == std::floor(v.get<double>()) &&
                     std::fabs(v.get<double>()) < 1e15)
                texts[field] = std::to_string(std::int64_t(v.get<double>()));
            else
                throw Error("texture size is a whole number of texels",
                            {.parameter = field, .value = shownJSON(v), .validRange = range});
        } else {
            if (!v.is_string())
                throw Error("expected a text in quotes",
                            {.parameter = field, .value = shownJSON(v)});
            texts[field] = v.get<std::string>();
        }
    }
    return variant(texts, format);
}

PlantFileOptions exportVariant(const httplib::Request& req, const std::string& format) {
    Texts texts;
    for (const std::string& field : exportVariantFields())
        if (req.has_param(field)) texts[field] = req.get_param_value(field);
    return variant(texts, format);
}

}  // namespace plantarch::builder
