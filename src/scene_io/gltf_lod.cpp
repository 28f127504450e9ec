// Levels of detail (MSFT_lod) and EXT_meshopt_compression for the glTF writer (gltf_lod.h).

#include "scene_io/gltf_lod.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "plantarch/Error.h"
#include "scene_io/scene_lod.h"

namespace plantarch::gltf {

namespace {

// Adds `n` to every index in the array `j` (or to the number `j`).
void shift(json& j, std::size_t n) {
    if (j.is_array())
        for (json& v : j) v = v.get<std::size_t>() + n;
    else
        j = j.get<std::size_t>() + n;
}

// The root's children of a document's scene: the plant nodes.
json plantNodes(const json& doc) {
    const std::size_t world = doc["scenes"][0]["nodes"][0].get<std::size_t>();
    return doc["nodes"][world].value("children", json::array());
}

// Which full-level node a level's plant node stands for: its plant ID, or its name (the
// node of the objects of no plant).
std::string plantKey(const json& node) {
    if (node.contains("extras") && node["extras"].contains("plantID"))
        return "plant " + node["extras"]["plantID"].dump();
    return "name " + node.value("name", std::string());
}

// Appends level document `d` (its buffer laid out from `base`) to `doc`; returns the new
// indices of its plant nodes by plantKey.
std::map<std::string, std::size_t> appendLevel(json& doc, json d, std::size_t base,
                                               std::size_t level) {
    const std::size_t views = doc["bufferViews"].size(), accessors = doc["accessors"].size(),
                      meshes = doc.value("meshes", json::array()).size(),
                      nodes = doc["nodes"].size(),
                      materials = doc.value("materials", json::array()).size();
    const bool sameMaterials = d.value("materials", json::array()).size() == materials;
    for (json& v : d["bufferViews"]) {
        v["byteOffset"] = v.value("byteOffset", std::size_t(0)) + base;
        doc["bufferViews"].push_back(std::move(v));
    }
    for (json& a : d["accessors"]) {
        shift(a["bufferView"], views);
        doc["accessors"].push_back(std::move(a));
    }
    json levelMeshes = d.value("meshes", json::array());
    for (json& m : levelMeshes) {
        for (json& p : m["primitives"]) {
            for (auto& [name, a] : p["attributes"].items()) shift(a, accessors);
            shift(p["indices"], accessors);
            if (!sameMaterials) shift(p["material"], materials);  // a level's own materials
        }
        doc["meshes"].push_back(std::move(m));
    }
    if (!sameMaterials)
        for (const json& m : d.value("materials", json::array())) doc["materials"].push_back(m);
    // The level's nodes but its root (the last node: its rotation is the full level's, which
    // MSFT_lod keeps as the parent of the node it swaps).
    const std::size_t world = d["scenes"][0]["nodes"][0].get<std::size_t>();
    if (world + 1 != d["nodes"].size())
        throw std::logic_error("glTF level of detail: the root is not the last node");
    std::map<std::string, std::size_t> byPlant;
    for (const json& n : d["nodes"][world].value("children", json::array()))
        byPlant[plantKey(d["nodes"][n.get<std::size_t>()])] = n.get<std::size_t>() + nodes;
    d["nodes"].erase(world);
    for (json& n : d["nodes"]) {
        if (n.contains("mesh")) shift(n["mesh"], meshes);
        if (n.contains("children")) shift(n["children"], nodes);
        if (!n.contains("mesh"))
            n["name"] = n.value("name", std::string()) + "_lod" + std::to_string(level);
        doc["nodes"].push_back(std::move(n));
    }
    return byPlant;
}

}  // namespace

void addLevels(json& doc, Buffer& buffer, const Scene& full, const GltfOptions& options,
               Levels& keep, const CollectLevel& collect, const LevelDocument& document) {
    if (options.levels.empty()) return;
    checkGltfLevels(options.levels);
    if (full.animated || full.frames.size() != 1)
        throw Error("levels of detail are not written with a growth animation",
                    {.parameter = "levels", .validRange = "no levels with frames"});
    if (!options.skeletons.empty())
        throw Error("levels of detail are not written with skins",
                    {.parameter = "levels", .validRange = "no levels with skeletons"});
    GltfOptions levelOptions = options;
    levelOptions.levels.clear();
    levelOptions.meshoptCompression = false;
    levelOptions.textures = false;  // the full level's materials serve every level
    levelOptions.progress = nullptr;
    const json fullPlants = plantNodes(doc);
    std::map<std::string, std::size_t> fullByPlant;
    for (const json& n : fullPlants) fullByPlant[plantKey(doc["nodes"][n.get<std::size_t>()])] = n;
    for (std::size_t l = 0; l < options.levels.size(); ++l) {
        keep.contexts.push_back(io::lodLevel(*full.frames[0], options.levels[l]));
        keep.scenes.push_back(collect(keep.contexts.back(), levelOptions));
        Buffer& levelBuffer = keep.buffers.emplace_back();
        json d = document(keep.scenes.back(), levelOptions, levelBuffer);
        const std::size_t base = buffer.size();
        json unused = json::array();
        buffer.add(unused, levelBuffer.size(), 0,
                   [&levelBuffer](Sink& out) { levelBuffer.write(out); });
        const auto byPlant = appendLevel(doc, std::move(d), base, l + 1);
        for (const auto& [key, node] : fullByPlant) {
            const auto at = byPlant.find(key);
            if (at == byPlant.end()) continue;
            json& n = doc["nodes"][node];
            n["extensions"]["MSFT_lod"]["ids"].push_back(at->second);
        }
    }
    // Each full-level node with alternatives: the coverage below which each level shows,
    // then 0 (the last level is never culled).
    for (const auto& [key, node] : fullByPlant) {
        json& n = doc["nodes"][node];
        if (!n.contains("extensions")) continue;
        json coverage = json::array();
        for (std::size_t k = 0; k < n["extensions"]["MSFT_lod"]["ids"].size(); ++k)
            coverage.push_back(std::round(double(gltfLevelCoverage(options.levels, k)) * 1e6) /
                               1e6);
        coverage.push_back(0.0);
        n["extras"]["MSFT_screencoverage"] = coverage;
    }
    doc["buffers"] = {{{"byteLength", buffer.size()}}};
    json& used = doc["extensionsUsed"];
    if (!used.is_array()) used = json::array();
    used.push_back("MSFT_lod");
}

namespace {

// The bytes of one element of the views' data, from the first accessor that reads each view
// (0: no accessor), and whether it holds triangle indices.
struct ViewUse {
    std::size_t elementBytes = 0;
    bool triangles = false, image = false;
};

std::size_t componentBytes(int type) {
    switch (type) {
        case 5120:
        case 5121:
            return 1;
        case 5122:
        case 5123:
            return 2;
        default:
            return 4;
    }
}

std::size_t components(const std::string& type) {
    static const std::map<std::string, std::size_t> n = {{"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3},
                                                         {"VEC4", 4},   {"MAT2", 4}, {"MAT3", 9},
                                                         {"MAT4", 16}};
    const auto at = n.find(type);
    return at == n.end() ? 0 : at->second;
}

}  // namespace

Buffer compressMeshopt(json& doc, const Buffer& buffer) {
    if (!doc.contains("bufferViews") || buffer.size() == 0) return Buffer(buffer);
    std::string bin;
    ProgressSteps quiet(nullptr, "", 1.0);
    Sink sink(nullptr, &bin, quiet);
    buffer.write(sink);

    json& views = doc["bufferViews"];
    std::vector<ViewUse> use(views.size());
    for (const json& a : doc.value("accessors", json::array())) {
        if (!a.contains("bufferView")) continue;
        ViewUse& u = use[a["bufferView"].get<std::size_t>()];
        if (u.elementBytes) continue;
        u.elementBytes = componentBytes(a["componentType"].get<int>()) *
                         components(a["type"].get<std::string>());
        u.triangles =
            views[a["bufferView"].get<std::size_t>()].value("target", 0) == kElementArrayBuffer &&
            a["componentType"].get<int>() == kUInt && a["count"].get<std::size_t>() % 3 == 0;
    }
    for (const json& i : doc.value("images", json::array()))
        if (i.contains("bufferView")) use[i["bufferView"].get<std::size_t>()].image = true;
    for (const json& p : doc.value("meshes", json::array()))
        for (const json& prim : p["primitives"])
            if (prim.value("mode", 4) != 4 && prim.contains("indices")) {
                const std::size_t view =
                    doc["accessors"][prim["indices"].get<std::size_t>()]["bufferView"];
                use[view].triangles = false;
            }

    auto packed = std::make_shared<std::string>();
    std::size_t fallback = 0;
    bool any = false;
    std::vector<unsigned char> encoded;
    for (std::size_t i = 0; i < views.size(); ++i) {
        json& v = views[i];
        const std::size_t offset = v.value("byteOffset", std::size_t(0));
        const std::size_t length = v["byteLength"].get<std::size_t>();
        const char* data = bin.data() + offset;
        const ViewUse& u = use[i];
        std::size_t stride = u.triangles ? 4 : (u.elementBytes ? u.elementBytes : 4);
        const bool attributes =
            !u.triangles && stride % 4 == 0 && stride <= 256 && length % stride == 0 && !u.image;
        std::size_t size = 0;
        if (u.triangles) {
            const std::size_t count = length / 4;
            std::vector<unsigned> indices(count);
            std::memcpy(indices.data(), data, length);
            unsigned vertices = 0;
            for (unsigned k : indices) vertices = std::max(vertices, k + 1);
            encoded.resize(meshopt_encodeIndexBufferBound(count, vertices));
            size = meshopt_encodeIndexBuffer(encoded.data(), encoded.size(), indices.data(), count);
        } else if (attributes && length > 0) {
            encoded.resize(meshopt_encodeVertexBufferBound(length / stride, stride));
            size = meshopt_encodeVertexBuffer(encoded.data(), encoded.size(), data, length / stride,
                                              stride);
        }
        packed->resize(align8(packed->size()));
        if (size > 0 && size < length) {
            v["extensions"]["EXT_meshopt_compression"] = {
                {"buffer", 0},
                {"byteOffset", packed->size()},
                {"byteLength", size},
                {"byteStride", stride},
                {"count", length / stride},
                {"mode", u.triangles ? "TRIANGLES" : "ATTRIBUTES"}};
            packed->append(reinterpret_cast<const char*>(encoded.data()), size);
            v["buffer"] = 1;
            v["byteOffset"] = fallback;
            fallback = align8(fallback + length);
            any = true;
        } else {  // stored as it is, in the GLB's own buffer
            v["byteOffset"] = packed->size();
            packed->append(data, length);
        }
    }
    packed->resize(align8(packed->size()));
    doc["buffers"] = {{{"byteLength", packed->size()}}};
    if (any) {
        doc["buffers"].push_back(
            {{"byteLength", fallback},
             {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}});
        for (const char* list : {"extensionsUsed", "extensionsRequired"}) {
            json& l = doc[list];
            if (!l.is_array()) l = json::array();
            l.push_back("EXT_meshopt_compression");
        }
    }
    Buffer out;
    json unused = json::array();
    out.add(unused, packed->size(), 0,
            [packed](Sink& sinkOut) { sinkOut.write(packed->data(), packed->size()); });
    return out;
}

void decodeMeshopt(json& doc, std::vector<std::string>& buffers, const std::string& path) {
    auto views = doc.find("bufferViews");
    if (views == doc.end() || !views->is_array()) return;
    auto fail = [&](const std::string& what) {
        return Error("EXT_meshopt_compression: " + what, {.file = path});
    };
    auto whole = [&](const json& o, const char* key, std::uint64_t fallback) -> std::uint64_t {
        const auto it = o.find(key);
        if (it == o.end()) return fallback;
        if (!it->is_number_unsigned())
            throw fail(std::string("\"") + key + "\" is not a whole number");
        return it->get<std::uint64_t>();
    };
    for (json& v : *views) {
        if (!v.is_object() || !v.contains("extensions") || !v["extensions"].is_object() ||
            !v["extensions"].contains("EXT_meshopt_compression"))
            continue;
        const json& e = v["extensions"]["EXT_meshopt_compression"];
        if (!e.is_object()) throw fail("the extension is not an object");
        const std::uint64_t buffer = whole(e, "buffer", ~0ull), offset = whole(e, "byteOffset", 0),
                            length = whole(e, "byteLength", ~0ull),
                            stride = whole(e, "byteStride", 0), count = whole(e, "count", ~0ull);
        const std::string mode = e.value("mode", std::string()),
                          filter = e.value("filter", std::string("NONE"));
        if (buffer >= buffers.size()) throw fail("it names no buffer");
        const std::string& data = buffers[std::size_t(buffer)];
        if (offset > data.size() || length > data.size() - offset)
            throw fail("its data reaches past its buffer");
        const bool indices = mode == "TRIANGLES" || mode == "INDICES";
        if (!(mode == "ATTRIBUTES" || indices)) throw fail("unknown mode \"" + mode + "\"");
        if (indices ? (stride != 2 && stride != 4)
                    : (stride == 0 || stride % 4 != 0 || stride > 256))
            throw fail("byteStride " + std::to_string(stride) + " does not suit mode " + mode);
        if (count > (256 * length + 65536) / stride)
            throw fail("it would decode to more than 256 times its size");
        std::string out(std::size_t(count * stride), '\0');
        const auto* src = reinterpret_cast<const unsigned char*>(data.data() + offset);
        const int rc =
            mode == "TRIANGLES"
                ? (count % 3 ? -1
                             : meshopt_decodeIndexBuffer(out.data(), count, stride, src, length))
            : mode == "INDICES"
                ? meshopt_decodeIndexSequence(out.data(), count, stride, src, length)
                : meshopt_decodeVertexBuffer(out.data(), count, stride, src, length);
        if (rc != 0) throw fail("a view's data does not decode");
        if (filter == "OCTAHEDRAL" && !indices && (stride == 4 || stride == 8))
            meshopt_decodeFilterOct(out.data(), count, stride);
        else if (filter == "QUATERNION" && !indices && stride == 8)
            meshopt_decodeFilterQuat(out.data(), count, stride);
        else if (filter == "EXPONENTIAL" && !indices)
            meshopt_decodeFilterExp(out.data(), count, stride);
        else if (filter != "NONE")
            throw fail("filter \"" + filter + "\" does not suit mode " + mode + " and byteStride " +
                       std::to_string(stride));
        buffers.push_back(std::move(out));
        v["buffer"] = buffers.size() - 1;
        v["byteOffset"] = std::uint64_t(0);
    }
}

}  // namespace plantarch::gltf
