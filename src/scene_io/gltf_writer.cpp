// glTF 2.0 writer (.glb binary, .gltf with the buffer embedded) with labels a receiving tool
// reads: per-vertex _PLANT_ID, _OBJECT_ID and _ORGAN attributes, EXT_mesh_features feature
// IDs that index an EXT_structural_metadata property table (plant, object, organ, leaf,
// shoot, rank, node and age of every object, and the physiology's float data when the scene
// has them), and node extras with each plant's species, age and seed.
//
// Layout: a node per plant (its base as the translation, vertices relative to it) and one for
// the objects of no plant (trellis, obstacles, ground); under each, one mesh per organ kind,
// with one primitive per material. Few large meshes load fast (a viewer pays per draw call,
// not per triangle), and the organ kind is what a user toggles. Every array has its own
// buffer view, 8-byte aligned, written in order after the JSON by the function given when the
// view was laid out (gltf_internal.h), so the binary is streamed from the Context without
// building it whole (the .gltf form encodes it in base64).

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "core/atomic_file.h"
#include "core/image_file.h"
#include "core/parallel.h"
#include "core/progress_steps.h"
#include "core/value_text.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/OutputFormats.h"
#include "scene_io/export_common.h"
#include "scene_io/gltf_instancing.h"
#include "scene_io/gltf_internal.h"
#include "scene_io/gltf_lod.h"
#include "scene_io/gltf_skin.h"
#include "scene_io/instancing.h"

namespace plantarch::gltf {

int Buffer::add(json& views, std::size_t bytes, int target, Fill fill) {
    json v = {{"buffer", 0}, {"byteOffset", size_}, {"byteLength", bytes}};
    if (target) v["target"] = target;
    views.push_back(std::move(v));
    blocks_.push_back({bytes, std::move(fill)});
    size_ = align8(size_ + bytes);
    return int(views.size()) - 1;
}

void Buffer::write(Sink& out) const {
    for (const Block& block : blocks_) {
        const std::size_t start = out.written();
        block.fill(out);
        if (out.written() - start != block.bytes)
            throw std::logic_error("glTF buffer view written with the wrong size");
        out.pad();
    }
}

json accessor(int view, int componentType, std::size_t count, const char* type) {
    return {
        {"bufferView", view}, {"componentType", componentType}, {"count", count}, {"type", type}};
}

EmbeddedImage embeddedImage(const std::string& path) {
    io::DecodedImage image = io::readTextureFile(path);
    return {std::move(image.bytes),
            image.format == io::ImageFormat::PNG ? "image/png" : "image/jpeg"};
}

}  // namespace plantarch::gltf

namespace plantarch {

namespace {
constexpr std::pair<NodeLevel, const char*> kNodeLevelNames[] = {
    {NodeLevel::Plant, "plant"}, {NodeLevel::Kind, "kind"}, {NodeLevel::Organ, "organ"}};
}  // namespace

const char* nodeLevelName(NodeLevel level) {
    for (const auto& [l, name] : kNodeLevelNames)
        if (l == level) return name;
    return "kind";
}

std::optional<NodeLevel> nodeLevelFromName(std::string_view name) {
    for (const auto& [l, text] : kNodeLevelNames)
        if (name == text) return l;
    return std::nullopt;
}

}  // namespace plantarch

namespace plantarch::gltf {

json plantNode(const Node& node, const json& children) {
    json parent;
    if (node.plant >= 0) {
        const std::string species = node.info ? node.info->species : "";
        parent["name"] = (species.empty() ? "plant" : species) + "_" + std::to_string(node.plant);
        json extras = {{"plantID", node.plant}};
        if (node.info) {
            extras["species"] = species;
            extras["age"] = node.info->age;
            extras["seed"] = node.info->seed;
        }
        parent["extras"] = extras;
        if (node.base != vec3(0.0f))
            parent["translation"] = {node.base.x, node.base.y, node.base.z};
    } else {
        parent["name"] = "scene";
    }
    if (!children.empty()) parent["children"] = children;
    return parent;
}

namespace {

std::string base64(const std::string& bytes) {
    static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    std::size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        const std::uint32_t v = std::uint32_t(std::uint8_t(bytes[i])) << 16 |
                                std::uint32_t(std::uint8_t(bytes[i + 1])) << 8 |
                                std::uint8_t(bytes[i + 2]);
        out += table[v >> 18];
        out += table[(v >> 12) & 63];
        out += table[(v >> 6) & 63];
        out += table[v & 63];
    }
    if (i < bytes.size()) {
        std::uint32_t v = std::uint32_t(std::uint8_t(bytes[i])) << 16;
        if (i + 1 < bytes.size()) v |= std::uint32_t(std::uint8_t(bytes[i + 1])) << 8;
        out += table[v >> 18];
        out += table[(v >> 12) & 63];
        out += i + 1 < bytes.size() ? table[(v >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}

// The records and nodes of one frame's Context.
void collectFrame(Scene& s, std::uint32_t frame, const std::vector<GltfPlant>& plants,
                  const GltfOptions& options) {
    const Context& ctx = *s.frames[frame];
    const std::vector<ObjectID> ids = io::exportedObjects(ctx, options.includeHidden);
    const io::LabelReader labelsOf(ctx);
    bool floatData[kOptionalCount];  // data of another type counts as absent, as for labels
    for (std::size_t c = 0; c < kOptionalCount; ++c)
        floatData[c] = ctx.objectDataType(kOptionalColumns[c].name) == DataType::Float;
    const std::size_t firstNode = s.nodes.size();
    std::map<std::int32_t, std::size_t> nodeOf;
    for (const GltfPlant& p : plants) {
        nodeOf.emplace(p.id, s.nodes.size());
        s.nodes.push_back({frame, p.id, p.base, p});
    }
    std::map<MaterialID, std::size_t> materialOf;
    for (ObjectID id : ids) {
        const ObjectView o = ctx.object(id);
        auto [m, fresh] = materialOf.emplace(o.material, 0);
        if (fresh) {
            const Material& mat = ctx.material(o.material);
            const auto at = std::find(s.materials.begin(), s.materials.end(), mat);
            m->second = std::size_t(at - s.materials.begin());
            if (at == s.materials.end()) s.materials.push_back(mat);
        }
        const io::ObjectLabels l = labelsOf(id);
        ObjectRecord r{id,     l.plant, l.organ,   l.leaf, l.shoot,        l.rank,
                       l.node, l.age,   m->second, frame,  !o.uvs.empty(), {}};
        for (std::size_t c = 0; c < kOptionalCount; ++c) {
            const std::optional<float> v =
                floatData[c] ? ctx.objectDataFloat(id, kOptionalColumns[c].name) : std::nullopt;
            r.optional[c] = v.value_or(kNoData);
            if (v) s.hasColumn[c] = true;
        }
        if (!nodeOf.count(r.plant)) {
            nodeOf.emplace(r.plant, s.nodes.size());
            s.nodes.push_back({frame, r.plant, vec3(0.0f), std::nullopt});
        }
        s.records.push_back(r);
    }
    // Plants in ID order, the objects of no plant last.
    std::stable_sort(s.nodes.begin() + std::ptrdiff_t(firstNode), s.nodes.end(),
                     [](const Node& a, const Node& b) {
                         return std::make_pair(a.plant < 0, a.plant) <
                                std::make_pair(b.plant < 0, b.plant);
                     });
}

Scene collect(const std::vector<AnimationFrame>& frames, const GltfOptions& options) {
    Scene s;
    for (std::uint32_t f = 0; f < frames.size(); ++f) {
        s.frames.push_back(frames[f].context);
        s.days.push_back(frames[f].day);
        collectFrame(s, f, frames[f].plants, options);
    }
    std::map<std::pair<std::size_t, std::int32_t>, std::size_t> nodeOf;
    for (std::size_t i = 0; i < s.nodes.size(); ++i)
        nodeOf[{s.nodes[i].frame, s.nodes[i].plant}] = i;

    std::map<std::tuple<std::size_t, std::uint8_t, std::size_t>, std::size_t> primitiveOf;
    for (std::size_t i = 0; i < s.records.size(); ++i) {
        const ObjectRecord& r = s.records[i];
        const std::size_t node = nodeOf[{r.frame, r.plant}];
        // One mesh per plant: the organ kinds together (kind 0 stands for all).
        const std::uint8_t kind = options.nodes == NodeLevel::Plant ? 0 : r.organ;
        auto [it, fresh] = primitiveOf.emplace(std::make_tuple(node, kind, r.material), 0);
        if (fresh) {
            it->second = s.primitives.size();
            s.primitives.push_back({node, kind, r.material, {}});
        }
        Primitive& p = s.primitives[it->second];
        p.objects.push_back(i);
        const ObjectView o = s.object(r);
        p.vertices += o.positions.size();
        p.triangles += o.triangleCount();
        p.uvs = p.uvs && r.uvs && options.uvs;
    }
    for (const Material& mat : s.materials)  // the texture images, in material order
        if (!mat.texture.empty() && options.textures &&
            std::find(s.images.begin(), s.images.end(), mat.texture) == s.images.end())
            s.images.push_back(mat.texture);
    for (const std::string& image : s.images) s.imageData.push_back(embeddedImage(image));
    std::stable_sort(s.primitives.begin(), s.primitives.end(),
                     [](const Primitive& a, const Primitive& b) {
                         return std::tie(a.node, a.organ) < std::tie(b.node, b.organ);
                     });
    return s;
}

json schema(const Scene& s) {
    json values = json::array();
    for (std::size_t i = 0; i < kOrganLabels.size(); ++i)
        values.push_back({{"name", std::string(kOrganLabels[i])}, {"value", i}});
    auto scalar = [](const char* type, const char* description) {
        return json{{"type", "SCALAR"}, {"componentType", type}, {"description", description}};
    };
    json properties = {
        {"plant", scalar("INT32", "plant ID (-1: not a plant organ)")},
        {"object", scalar("UINT32", "object ID")},
        {"organ", {{"type", "ENUM"}, {"enumType", "organ_kind"}, {"description", "organ kind"}}},
        {"leaf", scalar("INT32", "leaf ID within the plant (-1: not a leaf)")},
        {"shoot", scalar("INT32", "shoot ID within the plant (-1: none)")},
        {"rank", scalar("INT32", "shoot rank, 0 for the base stem (-1: none)")},
        {"node", scalar("INT32", "node (phytomer) index on the shoot (-1: none)")},
        {"age", scalar("FLOAT32", "organ age, days (-1: unknown)")}};
    for (std::size_t c = 0; c < kOptionalCount; ++c)
        if (s.hasColumn[c]) {
            json p = scalar("FLOAT32", kOptionalColumns[c].description);
            p["noData"] = kNoData;
            properties[kOptionalColumns[c].name] = std::move(p);
        }
    return {{"id", "plantarch"},
            {"enums", {{"organ_kind", {{"valueType", "UINT8"}, {"values", values}}}}},
            {"classes",
             {{"organ",
               {{"description", "One organ object: a leaf, an internode, a flower ..."},
                {"properties", properties}}}}}};
}

// Smooth normals of every object, on all threads (each object its own slice).
void computeNormals(Scene& s) {
    s.normalAt.assign(s.records.size() + 1, 0);
    for (std::size_t i = 0; i < s.records.size(); ++i)
        s.normalAt[i + 1] = s.normalAt[i] + s.object(i).positions.size();
    s.normals.resize(s.normalAt.back());
    const std::ptrdiff_t n = std::ptrdiff_t(s.records.size());
    ParallelErrors errors;
#pragma omp parallel
    {
        std::vector<vec3> one;
#pragma omp for schedule(dynamic, 64)
        for (std::ptrdiff_t i = 0; i < n; ++i)
            errors.run(i, [&] {
                smoothNormals(s.object(std::size_t(i)), one);
                std::copy(one.begin(), one.end(),
                          s.normals.begin() + std::ptrdiff_t(s.normalAt[std::size_t(i)]));
            });
    }
    errors.rethrow();
}

// Images (their bytes first in the buffer) and materials.
void addMaterials(GltfArrays& d, const Scene& s, const GltfOptions& options, Buffer& buffer) {
    if (options.appearance.style == MaterialStyle::Textured)
        return addTexturedMaterials(d, s, options, buffer);  // gltf_materials.cpp
    for (const EmbeddedImage& image : s.imageData) {
        const int view = buffer.add(d.views, image.bytes.size(), 0, [&image](Sink& out) {
            out.write(image.bytes.data(), image.bytes.size());
        });
        d.images.push_back({{"bufferView", view}, {"mimeType", image.mimeType}});
        d.textures.push_back({{"source", d.images.size() - 1}});
    }
    for (const Material& mat : s.materials) {
        json pbr = {{"baseColorFactor",
                     {linear(mat.color.x), linear(mat.color.y), linear(mat.color.z), 1.0}},
                    {"metallicFactor", 0.0},
                    {"roughnessFactor", 0.9}};
        if (!mat.texture.empty() && options.textures) {
            const auto at = std::find(s.images.begin(), s.images.end(), mat.texture);
            pbr["baseColorTexture"] = {{"index", at - s.images.begin()}};
            pbr["baseColorFactor"] = {1.0, 1.0, 1.0, 1.0};
        }
        json material = {{"pbrMetallicRoughness", pbr}, {"doubleSided", true}};
        if (!mat.name.empty()) material["name"] = mat.name;
        if (!mat.texture.empty() && options.textures) material["alphaMode"] = "MASK";
        d.materials.push_back(std::move(material));
    }
}

// One mesh per node and organ, a primitive per Scene primitive; returns each node's meshes.
std::vector<json> addMeshes(GltfArrays& d, const Scene& s, const GltfOptions& options,
                            Buffer& buffer) {
    std::vector<json> nodeMeshes(s.nodes.size());
    std::map<std::pair<std::size_t, std::uint8_t>, int> meshOf;
    for (const Primitive& p : s.primitives) {
        const Node& node = s.nodes[p.node];
        vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
        for (std::size_t i : p.objects)
            for (const vec3& v : s.object(i).positions) {
                lo = glm::min(lo, v - node.base);
                hi = glm::max(hi, v - node.base);
            }
        const vec3 base = node.base;
        // Each block streams the primitive's objects in order.
        auto eachObject = [&s, &p](auto&& f) {
            for (std::size_t i : p.objects) f(i, s.object(i));
        };
        json attributes;
        auto vertexView = [&](std::size_t bytesPerVertex, Buffer::Fill fill) {
            return buffer.add(d.views, p.vertices * bytesPerVertex, kArrayBuffer, std::move(fill));
        };
        int view = vertexView(12, [eachObject, base](Sink& out) {
            eachObject([&](std::size_t, const ObjectView& o) {
                if (base == vec3(0.0f)) {
                    out.write(o.positions.data(), o.positions.size_bytes());
                    return;
                }
                writeValues<vec3>(out, o.positions.size(),
                                  [&](std::size_t k) { return o.positions[k] - base; });
            });
        });
        json position = accessor(view, kFloat, p.vertices, "VEC3");
        position["min"] = {lo.x, lo.y, lo.z};
        position["max"] = {hi.x, hi.y, hi.z};
        d.accessors.push_back(position);
        attributes["POSITION"] = d.accessors.size() - 1;
        if (options.normals) {
            view = vertexView(12, [eachObject, &s](Sink& out) {
                eachObject([&](std::size_t i, const ObjectView& o) {
                    out.write(s.normals.data() + s.normalAt[i], o.positions.size() * sizeof(vec3));
                });
            });
            d.accessors.push_back(accessor(view, kFloat, p.vertices, "VEC3"));
            attributes["NORMAL"] = d.accessors.size() - 1;
        }
        addTangents(d, s, options, buffer, p, attributes);  // gltf_materials.cpp
        if (p.uvs) {
            view = vertexView(8, [eachObject](Sink& out) {
                eachObject([&](std::size_t, const ObjectView& o) {
                    out.write(o.uvs.data(), o.uvs.size_bytes());
                });
            });
            d.accessors.push_back(accessor(view, kFloat, p.vertices, "VEC2"));
            attributes["TEXCOORD_0"] = d.accessors.size() - 1;
        }
        json extensions;
        if (options.labels) {
            // Per vertex, as floats: the plant, the object, the organ and the feature (the
            // object's row in the property table).
            const std::pair<const char*, float (*)(const Scene&, std::size_t)> labels[] = {
                {"_PLANT_ID",
                 [](const Scene& sc, std::size_t i) { return float(sc.records[i].plant); }},
                {"_OBJECT_ID",
                 [](const Scene& sc, std::size_t i) { return float(sc.records[i].id); }},
                {"_ORGAN",
                 [](const Scene& sc, std::size_t i) { return float(sc.records[i].organ); }},
                {"_FEATURE_ID_0", [](const Scene&, std::size_t i) { return float(i); }}};
            for (const auto& [name, label] : labels) {
                view = vertexView(4, [eachObject, &s, label = label](Sink& out) {
                    eachObject([&](std::size_t i, const ObjectView& o) {
                        const float v = label(s, i);
                        writeValues<float>(out, o.positions.size(), [v](std::size_t) { return v; });
                    });
                });
                d.accessors.push_back(accessor(view, kFloat, p.vertices, "SCALAR"));
                attributes[name] = d.accessors.size() - 1;
            }
            extensions["EXT_mesh_features"] = {
                {"featureIds",
                 {{{"featureCount", p.objects.size()}, {"attribute", 0}, {"propertyTable", 0}}}}};
        }
        addSkinAttributes(d, s, options, buffer, p, attributes);  // gltf_skin.cpp
        const int indexView =
            buffer.add(d.views, p.triangles * 12, kElementArrayBuffer, [eachObject](Sink& out) {
                std::uint32_t first = 0;
                eachObject([&](std::size_t, const ObjectView& o) {
                    writeValues<std::uint32_t>(out, o.indices.size(),
                                               [&](std::size_t k) { return first + o.indices[k]; });
                    first += std::uint32_t(o.positions.size());
                });
            });
        d.accessors.push_back(accessor(indexView, kUInt, p.triangles * 3, "SCALAR"));
        json primitive = {{"attributes", attributes},
                          {"indices", d.accessors.size() - 1},
                          {"material", p.material},
                          {"mode", 4}};
        if (!extensions.empty()) primitive["extensions"] = extensions;
        const auto key = std::make_pair(p.node, p.organ);
        auto [it, fresh] = meshOf.emplace(key, int(d.meshes.size()));
        if (fresh) {
            d.meshes.push_back(
                {{"name", options.nodes == NodeLevel::Plant ? std::string("plant")
                                                            : std::string(kOrganLabels[p.organ])},
                 {"primitives", json::array()}});
            nodeMeshes[p.node].push_back(it->second);
        }
        d.meshes[std::size_t(it->second)]["primitives"].push_back(std::move(primitive));
    }
    return nodeMeshes;
}

// One child node per mesh under each plant's node; returns the plant nodes.
json addPlantNodes(GltfArrays& d, const Scene& s, const std::vector<json>& nodeMeshes) {
    json roots = json::array();
    for (std::size_t n = 0; n < s.nodes.size(); ++n) {
        json children = json::array();
        for (const json& mesh : nodeMeshes[n]) {
            d.nodes.push_back(
                {{"mesh", mesh}, {"name", d.meshes[mesh.get<std::size_t>()]["name"]}});
            children.push_back(d.nodes.size() - 1);
        }
        d.nodes.push_back(plantNode(s.nodes[n], children));
        roots.push_back(d.nodes.size() - 1);
    }
    return roots;
}

// The JSON document and the buffer's layout.
json document(const Scene& s, const GltfOptions& options, Buffer& buffer) {
    json doc;
    doc["asset"] = {{"version", "2.0"}, {"generator", "plantarch"}};
    GltfArrays d;
    addMaterials(d, s, options, buffer);
    json roots = json::array(), animation;
    if (s.organNodes) {
        animation = addOrganNodes(d, s, options, buffer, roots);  // gltf_organs.cpp
    } else {
        const std::vector<json> nodeMeshes = addMeshes(d, s, options, buffer);
        roots = addPlantNodes(d, s, nodeMeshes);
    }
    const SkinNodes skins = addSkins(d, s, options, buffer, roots);  // gltf_skin.cpp

    if (options.labels && !s.records.empty()) {  // an empty table is not allowed
        const std::size_t features = s.records.size();
        json properties;
        // One column per property, a value per object (the table's row).
        auto column = [&](const char* name, auto type, auto get) {
            using T = decltype(type);
            properties[name] = {
                {"values", buffer.add(d.views, features * sizeof(T), 0, [&s, get](Sink& out) {
                     writeValues<T>(out, s.records.size(),
                                    [&](std::size_t i) { return get(s.records[i]); });
                 })}};
        };
        column("plant", std::int32_t{}, [](const ObjectRecord& r) { return r.plant; });
        column("object", std::uint32_t{}, [](const ObjectRecord& r) { return r.id; });
        column("organ", std::uint8_t{}, [](const ObjectRecord& r) { return r.organ; });
        column("leaf", std::int32_t{}, [](const ObjectRecord& r) { return r.leaf; });
        column("shoot", std::int32_t{}, [](const ObjectRecord& r) { return r.shoot; });
        column("rank", std::int32_t{}, [](const ObjectRecord& r) { return r.rank; });
        column("node", std::int32_t{}, [](const ObjectRecord& r) { return r.node; });
        column("age", float{}, [](const ObjectRecord& r) { return r.age; });
        for (std::size_t c = 0; c < kOptionalCount; ++c)
            if (s.hasColumn[c])
                column(kOptionalColumns[c].name, float{},
                       [c](const ObjectRecord& r) { return r.optional[c]; });
        doc["extensions"]["EXT_structural_metadata"] = {
            {"schema", schema(s)},
            {"propertyTables",
             {{{"class", "organ"}, {"count", features}, {"properties", properties}}}}};
        doc["extensionsUsed"] = {"EXT_mesh_features", "EXT_structural_metadata"};
    }
    declareInstancing(doc, d.nodes);  // gltf_instancing.cpp

    doc["scene"] = 0;
    // z up in plantarch, y up in glTF: the root turns the scene about x by -90 degrees.
    json world = {{"name", "plantarch"}, {"rotation", {-0.70710678, 0.0, 0.0, 0.70710678}}};
    if (!roots.empty()) world["children"] = roots;  // an empty list is not allowed
    d.nodes.push_back(world);
    json sceneRoots = json::array({d.nodes.size() - 1});
    for (const json& r : skins.roots) sceneRoots.push_back(r);  // skinned meshes: roots
    doc["scenes"] = {{{"nodes", sceneRoots}}};
    if (!skins.skins.empty()) doc["skins"] = skins.skins;
    doc["nodes"] = d.nodes;
    if (!animation.empty()) doc["animations"] = {animation};
    if (!skins.animation.empty()) doc["animations"].push_back(skins.animation);  // wind
    if (!d.meshes.empty()) doc["meshes"] = d.meshes;
    if (!d.materials.empty()) doc["materials"] = d.materials;
    if (!d.accessors.empty()) doc["accessors"] = d.accessors;
    if (!d.views.empty()) doc["bufferViews"] = d.views;
    if (!d.images.empty()) {
        doc["images"] = d.images;
        doc["textures"] = d.textures;
        doc["samplers"] = {{{"magFilter", 9729}, {"minFilter", 9987}}};
        for (json& t : doc["textures"]) t["sampler"] = 0;
        // The texture atlas (gltf_materials.cpp): a viewer ignoring the transforms would draw
        // the wrong part of it, so the extension is required.
        if (std::any_of(d.materials.begin(), d.materials.end(), [](const json& m) {
                const auto pbr = m.find("pbrMetallicRoughness");
                if (pbr == m.end() || !pbr->contains("baseColorTexture")) return false;
                return (*pbr)["baseColorTexture"].contains("extensions");
            }))
            for (const char* list : {"extensionsUsed", "extensionsRequired"}) {
                json& l = doc[list];
                if (!l.is_array()) l = json::array();
                l.push_back("KHR_texture_transform");
            }
    }
    if (buffer.size()) doc["buffers"] = {{{"byteLength", buffer.size()}}};
    return doc;
}

void write(Scene& scene, const std::string& path, const GltfOptions& options) {
    if (scene.records.size() >= (std::size_t(1) << 24))
        throw Error("too many objects for float labels in glTF",
                    {.file = path,
                     .value = std::to_string(scene.records.size()),
                     .validRange = "fewer than 16777216 objects"});
    if (scene.organNodes && !scene.animated && !options.skeletons.empty())
        throw Error("a node per organ cannot be written with a skin",
                    {.file = path, .validRange = "skins with a node per plant or organ kind"});
    if (scene.organNodes && !options.levels.empty())
        throw Error(
            "a node per organ cannot be written with levels of detail",
            {.file = path, .validRange = "levels of detail with a node per plant or organ kind"});
    if (options.normals && !scene.organNodes) computeNormals(scene);
    checkSkins(scene, options, path);  // gltf_skin.cpp
    Buffer buffer;
    json doc = document(scene, options, buffer);
    Levels levels;  // levels of detail and compression (gltf_lod.cpp)
    addLevels(
        doc, buffer, scene, options, levels,
        [](const Context& c, const GltfOptions& o) {
            return collect({AnimationFrame{&c, 0.0, o.plants}}, o);
        },
        [](Scene& s, const GltfOptions& o, Buffer& b) {
            if (o.normals) computeNormals(s);
            return document(s, o, b);
        });
    if (options.meshoptCompression) buffer = compressMeshopt(doc, buffer);
    io::AtomicFile file(path);
    ProgressSteps steps(options.progress, "writing glTF", double(buffer.size()));
    if (lowerExtension(path) == ".gltf") {
        std::string bytes;
        Sink sink(nullptr, &bytes, steps);
        buffer.write(sink);
        if (!bytes.empty())
            doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64(bytes);
        file.write(doc.dump());
        file.commit();
        steps.finish();
        return;
    }
    std::string text = doc.dump();
    text.append((4 - text.size() % 4) % 4, ' ');
    const std::uint32_t binLength = std::uint32_t(buffer.size());
    const std::uint32_t total =
        12 + 8 + std::uint32_t(text.size()) + (binLength ? 8 + binLength : 0);
    const std::uint32_t header[3] = {0x46546C67u, 2u, total};  // "glTF", version 2
    file.write(header, sizeof header);
    const std::uint32_t jsonChunk[2] = {std::uint32_t(text.size()), 0x4E4F534Au};  // "JSON"
    file.write(jsonChunk, sizeof jsonChunk);
    file.write(text);
    if (binLength) {
        const std::uint32_t binChunk[2] = {binLength, 0x004E4942u};  // "BIN"
        file.write(binChunk, sizeof binChunk);
        Sink sink(&file, nullptr, steps);
        buffer.write(sink);
    }
    file.commit();
    steps.finish();
}

void checkExtension(const std::string& path) {
    requireOutputFormat(path, {".glb", ".gltf"}, "writeGLTF writes glTF, binary or text");
}

}  // namespace

}  // namespace plantarch::gltf

namespace plantarch {

using gltf::Scene;

void writeGLTF(const Context& context, const std::string& path, const GltfOptions& options) {
    gltf::checkExtension(path);
    io::checkInstancing(path, options.nodes, options.instancing, false);
    Scene scene = gltf::collect({AnimationFrame{&context, 0.0, options.plants}}, options);
    if (options.nodes == NodeLevel::Organ) gltf::collectOrgans(scene, options);
    gltf::write(scene, path, options);
}

void writeGLTF(const std::vector<AnimationFrame>& frames, const std::string& path,
               const GltfOptions& options, const AnimationOptions& animation) {
    gltf::checkExtension(path);
    io::checkAnimation(frames, animation, path);
    io::checkInstancing(path, NodeLevel::Organ, options.instancing, true);
    Scene scene = gltf::collect(frames, options);
    scene.animated = true;
    scene.framesPerSecond = animation.framesPerSecond;
    gltf::collectOrgans(scene, options);  // an animation has a node per organ
    gltf::write(scene, path, options);
}

}  // namespace plantarch