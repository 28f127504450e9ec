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
// buffer view, 8-byte aligned, written in order after the JSON, so the binary is streamed
// from the Context without building it whole (the .gltf form encodes it in base64).

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

namespace plantarch {

namespace {

using json = nlohmann::json;

static_assert(std::endian::native == std::endian::little, "glTF buffers are little-endian");

constexpr int kFloat = 5126, kUInt = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

// The property table's optional columns: float object data a physiology season leaves (on
// leaves, or on every object of a shoot with a carbohydrate budget). A column is written when
// any exported object carries its data (as a float); the others' rows hold kNoData, declared
// as the property's noData. A scene with none of them is written as before.
struct OptionalColumn {
    const char* name;  // the object data's label, and the column's name
    const char* description;
};
constexpr OptionalColumn kOptionalColumns[] = {
    {"absorbed_par",
     "PAR absorbed, umol m-2 s-1, mean over the last simulated day's daylight hours"},
    {"sunlit_fraction", "sunlit share of the leaf, 0 to 1, mean over the same hours"},
    {"net_photosynthesis", "net CO2 assimilation, umol m-2 s-1, mean over the same hours"},
    {"carbohydrate_concentration",
     "the shoot's sugar and starch per structural carbon of its wood, mol C / mol C"},
};
constexpr std::size_t kOptionalCount = std::size(kOptionalColumns);
constexpr float kNoData = -9999.0f;

// What one exported object contributes, and where.
struct ObjectRecord {
    ObjectID id;
    std::int32_t plant;
    std::uint8_t organ;
    std::int32_t leaf, shoot, rank, node;
    float age;
    std::size_t material;  // index into Scene::materials
    std::uint32_t frame;
    bool uvs;
    std::array<float, kOptionalCount> optional;  // kNoData where the object has no such data
};

// One primitive: the objects of one (node, organ kind, material).
struct Primitive {
    std::size_t node;
    std::uint8_t organ;
    std::size_t material;
    std::vector<std::size_t> objects;  // indices into the records
    std::size_t vertices = 0, triangles = 0;
    bool uvs = true;
};

struct Node {
    std::size_t frame;
    std::int32_t plant;  // -1: the objects of no plant
    vec3 base{0.0f};
    std::optional<GltfPlant> info;  // species, age and seed, when given
};

float linear(float srgb) {
    const float c = std::clamp(srgb, 0.0f, 1.0f);
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

std::size_t align8(std::size_t n) {
    return (n + 7) & ~std::size_t(7);
}

// A texture image as embedded: the bytes of a file that decoded as a PNG or JPEG image.
struct EmbeddedImage {
    std::string bytes;
    const char* mimeType;
};

EmbeddedImage embeddedImage(const std::string& path) {
    io::DecodedImage image = io::readTextureFile(path);
    return {std::move(image.bytes),
            image.format == io::ImageFormat::PNG ? "image/png" : "image/jpeg"};
}

// The byte blocks of the binary buffer, in order; each is produced when written.
class Buffer {
public:
    /// Reserves a block of `bytes` and returns its view index.
    int add(json& views, std::size_t bytes, int target) {
        json v = {{"buffer", 0}, {"byteOffset", size_}, {"byteLength", bytes}};
        if (target) v["target"] = target;
        views.push_back(std::move(v));
        sizes_.push_back(bytes);
        size_ = align8(size_ + bytes);
        return int(views.size()) - 1;
    }
    std::size_t size() const { return size_; }
    std::size_t viewSize(int view) const { return sizes_[std::size_t(view)]; }

private:
    std::size_t size_ = 0;
    std::vector<std::size_t> sizes_;
};

// Writes bytes to a .glb file or collects them for a .gltf's base64. Blocks are filled in
// place (reserve, then commit), so each byte is copied once on its way to the file.
class Sink {
public:
    static constexpr std::size_t kBlock = io::AtomicFile::kMaxReserve;

    Sink(io::AtomicFile* file, std::string* bytes, ProgressSteps& steps)
        : file_(file), bytes_(bytes), steps_(steps) {}
    void write(const void* data, std::size_t n) {
        if (file_)
            file_->write(data, n);
        else
            bytes_->append(static_cast<const char*>(data), n);
        written_ += n;
        steps_.at(double(written_));
    }
    /// Room for n <= kBlock bytes, to be filled and then handed back with commit(n).
    char* reserve(std::size_t n) {
        if (file_) return file_->reserve(n);
        bytes_->resize(written_ + n);
        return bytes_->data() + written_;
    }
    void commit(std::size_t n) {
        if (file_) file_->advance(file_->reserve(n) + n);
        written_ += n;
        steps_.at(double(written_));
    }
    void pad() {
        static const char zeros[8] = {};
        write(zeros, align8(written_) - written_);
    }

    /// Writes `count` elements of `size` bytes, made by fill(destination, first, n) in
    /// blocks of n elements.
    template <class Fill>
    void elements(std::size_t count, std::size_t size, Fill&& fill) {
        const std::size_t perBlock = kBlock / size;
        for (std::size_t first = 0; first < count; first += perBlock) {
            const std::size_t n = std::min(perBlock, count - first);
            fill(reserve(n * size), first, n);
            commit(n * size);
        }
    }

private:
    io::AtomicFile* file_;
    std::string* bytes_;
    ProgressSteps& steps_;  // by bytes of the buffer
    std::size_t written_ = 0;
};

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

struct Scene {
    std::vector<const Context*> frames;
    std::vector<double> days;  // the frames' times
    bool animated = false;
    double framesPerSecond = 24.0;
    std::vector<ObjectRecord> records;
    std::vector<Node> nodes;
    std::vector<Primitive> primitives;
    std::vector<Material> materials;               // in glTF material order
    std::vector<std::string> images;               // texture files, in glTF image order
    std::vector<EmbeddedImage> imageData;          // each decoded and checked, as embedded
    std::array<bool, kOptionalCount> hasColumn{};  // the optional columns written

    ObjectView object(const ObjectRecord& r) const { return frames[r.frame]->object(r.id); }
    ObjectView object(std::size_t record) const { return object(records[record]); }
};

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
        auto [it, fresh] = primitiveOf.emplace(std::make_tuple(node, r.organ, r.material), 0);
        if (fresh) {
            it->second = s.primitives.size();
            s.primitives.push_back({node, r.organ, r.material, {}});
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

std::string frameName(double day) {
    std::string text = text::formatDouble(day);
    for (char& c : text)
        if (c == '.') c = '_';
    return "day_" + text;
}

// The keys of frame f's scale: 0 (hidden) or 1 (shown), held from each time to the next.
// Frame f is shown from f / rate seconds to (f + 1) / rate; the last frame stays shown.
struct FrameKey {
    float time, scale;
};
std::vector<FrameKey> frameKeys(const Scene& s, std::size_t f) {
    const std::size_t n = s.frames.size();
    const auto time = [&](std::size_t i) { return float(double(i) / s.framesPerSecond); };
    std::vector<FrameKey> keys;
    if (f > 0) keys.push_back({0.0f, 0.0f});
    keys.push_back({time(f), 1.0f});
    if (f + 1 < n) keys.push_back({time(f + 1), 0.0f});
    keys.push_back({time(n), f + 1 == n ? 1.0f : 0.0f});
    return keys;
}

json accessor(int view, int componentType, std::size_t count, const char* type) {
    return {
        {"bufferView", view}, {"componentType", componentType}, {"count", count}, {"type", type}};
}

// The arrays of the JSON document, filled in the order their buffer views are laid out.
struct GltfArrays {
    json views = json::array(), accessors = json::array(), meshes = json::array();
    json nodes = json::array(), materials = json::array();
    json textures = json::array(), images = json::array();
};

// Images (their bytes first in the buffer) and materials.
void addMaterials(GltfArrays& d, const Scene& s, const GltfOptions& options, Buffer& buffer) {
    for (const EmbeddedImage& image : s.imageData) {
        d.images.push_back({{"bufferView", buffer.add(d.views, image.bytes.size(), 0)},
                            {"mimeType", image.mimeType}});
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
        json attributes;
        auto vertexView = [&](std::size_t bytesPerVertex) {
            return buffer.add(d.views, p.vertices * bytesPerVertex, kArrayBuffer);
        };
        int view = vertexView(12);
        json position = accessor(view, kFloat, p.vertices, "VEC3");
        position["min"] = {lo.x, lo.y, lo.z};
        position["max"] = {hi.x, hi.y, hi.z};
        d.accessors.push_back(position);
        attributes["POSITION"] = d.accessors.size() - 1;
        if (options.normals) {
            d.accessors.push_back(accessor(vertexView(12), kFloat, p.vertices, "VEC3"));
            attributes["NORMAL"] = d.accessors.size() - 1;
        }
        if (p.uvs) {
            d.accessors.push_back(accessor(vertexView(8), kFloat, p.vertices, "VEC2"));
            attributes["TEXCOORD_0"] = d.accessors.size() - 1;
        }
        json extensions;
        if (options.labels) {
            for (const char* name : {"_PLANT_ID", "_OBJECT_ID", "_ORGAN", "_FEATURE_ID_0"}) {
                d.accessors.push_back(accessor(vertexView(4), kFloat, p.vertices, "SCALAR"));
                attributes[name] = d.accessors.size() - 1;
            }
            extensions["EXT_mesh_features"] = {
                {"featureIds",
                 {{{"featureCount", p.objects.size()}, {"attribute", 0}, {"propertyTable", 0}}}}};
        }
        const int indexView = buffer.add(d.views, p.triangles * 12, kElementArrayBuffer);
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
                {{"name", std::string(kOrganLabels[p.organ])}, {"primitives", json::array()}});
            nodeMeshes[p.node].push_back(it->second);
        }
        d.meshes[std::size_t(it->second)]["primitives"].push_back(std::move(primitive));
    }
    return nodeMeshes;
}

// One child node per mesh under each plant's node; returns each frame's plant nodes.
std::vector<json> addPlantNodes(GltfArrays& d, const Scene& s,
                                const std::vector<json>& nodeMeshes) {
    std::vector<json> frameChildren(s.frames.size(), json::array());
    for (std::size_t n = 0; n < s.nodes.size(); ++n) {
        const Node& node = s.nodes[n];
        json children = json::array();
        for (const json& mesh : nodeMeshes[n]) {
            d.nodes.push_back(
                {{"mesh", mesh}, {"name", d.meshes[mesh.get<std::size_t>()]["name"]}});
            children.push_back(d.nodes.size() - 1);
        }
        json parent;
        if (node.plant >= 0) {
            const std::string species = node.info ? node.info->species : "";
            parent["name"] =
                (species.empty() ? "plant" : species) + "_" + std::to_string(node.plant);
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
        d.nodes.push_back(std::move(parent));
        frameChildren[node.frame].push_back(d.nodes.size() - 1);
    }
    return frameChildren;
}

// With frames, a node per frame over its plants, shown on its days by a step animation of
// its scale; the root nodes go to `roots`. Returns the animation (empty without frames).
json addFrames(GltfArrays& d, const Scene& s, const std::vector<json>& frameChildren,
               Buffer& buffer, json& roots) {
    if (!s.animated) {
        roots = frameChildren.front();
        return json();
    }
    json channels = json::array(), samplers = json::array();
    for (std::size_t f = 0; f < s.frames.size(); ++f) {
        json frame = {{"name", frameName(s.days[f])}, {"extras", {{"day", s.days[f]}}}};
        if (!frameChildren[f].empty()) frame["children"] = frameChildren[f];
        const std::vector<FrameKey> keys = frameKeys(s, f);
        if (keys.back().scale == 0.0f) frame["scale"] = {0.0, 0.0, 0.0};
        d.nodes.push_back(std::move(frame));
        roots.push_back(d.nodes.size() - 1);
        json input =
            accessor(buffer.add(d.views, keys.size() * 4, 0), kFloat, keys.size(), "SCALAR");
        input["min"] = {keys.front().time};
        input["max"] = {keys.back().time};
        d.accessors.push_back(std::move(input));
        d.accessors.push_back(
            accessor(buffer.add(d.views, keys.size() * 12, 0), kFloat, keys.size(), "VEC3"));
        samplers.push_back({{"input", d.accessors.size() - 2},
                            {"output", d.accessors.size() - 1},
                            {"interpolation", "STEP"}});
        channels.push_back(
            {{"sampler", f}, {"target", {{"node", d.nodes.size() - 1}, {"path", "scale"}}}});
    }
    return {{"name", "growth"}, {"channels", channels}, {"samplers", samplers}};
}

// The JSON document and the buffer's layout.
json document(const Scene& s, const GltfOptions& options, Buffer& buffer) {
    json doc;
    doc["asset"] = {{"version", "2.0"}, {"generator", "plantarch"}};
    GltfArrays d;
    addMaterials(d, s, options, buffer);
    const std::vector<json> nodeMeshes = addMeshes(d, s, options, buffer);
    const std::vector<json> frameChildren = addPlantNodes(d, s, nodeMeshes);
    json roots = json::array();
    const json animation = addFrames(d, s, frameChildren, buffer, roots);

    if (options.labels) {
        const std::size_t features = s.records.size();
        json properties;
        const std::pair<const char*, std::size_t> columns[] = {
            {"plant", 4}, {"object", 4}, {"organ", 1}, {"leaf", 4},
            {"shoot", 4}, {"rank", 4},   {"node", 4},  {"age", 4}};
        for (const auto& [name, bytes] : columns)
            properties[name] = {{"values", buffer.add(d.views, features * bytes, 0)}};
        for (std::size_t c = 0; c < kOptionalCount; ++c)
            if (s.hasColumn[c])
                properties[kOptionalColumns[c].name] = {
                    {"values", buffer.add(d.views, features * sizeof(float), 0)}};
        doc["extensions"]["EXT_structural_metadata"] = {
            {"schema", schema(s)},
            {"propertyTables",
             {{{"class", "organ"}, {"count", features}, {"properties", properties}}}}};
        doc["extensionsUsed"] = {"EXT_mesh_features", "EXT_structural_metadata"};
    }

    doc["scene"] = 0;
    // z up in plantarch, y up in glTF: the root turns the scene about x by -90 degrees.
    json world = {{"name", "plantarch"},
                  {"rotation", {-0.70710678, 0.0, 0.0, 0.70710678}},
                  {"children", roots}};
    d.nodes.push_back(world);
    doc["scenes"] = {{{"nodes", {d.nodes.size() - 1}}}};
    doc["nodes"] = d.nodes;
    if (!animation.empty()) doc["animations"] = {animation};
    if (!d.meshes.empty()) doc["meshes"] = d.meshes;
    if (!d.materials.empty()) doc["materials"] = d.materials;
    if (!d.accessors.empty()) doc["accessors"] = d.accessors;
    if (!d.views.empty()) doc["bufferViews"] = d.views;
    if (!d.images.empty()) {
        doc["images"] = d.images;
        doc["textures"] = d.textures;
        doc["samplers"] = {{{"magFilter", 9729}, {"minFilter", 9987}}};
        for (json& t : doc["textures"]) t["sampler"] = 0;
    }
    if (buffer.size()) doc["buffers"] = {{{"byteLength", buffer.size()}}};
    return doc;
}

// The binary buffer, view by view in the order document() laid them out; each view is
// streamed object by object straight from the Context.
void writeBinary(const Scene& s, const GltfOptions& options, Sink& out) {
    for (const EmbeddedImage& image : s.imageData) {
        out.write(image.bytes.data(), image.bytes.size());
        out.pad();
    }
    // Normals of every object first, on all threads (each object's own slice).
    std::vector<vec3> normals;
    std::vector<std::size_t> normalAt(s.records.size() + 1, 0);
    if (options.normals) {
        for (std::size_t i = 0; i < s.records.size(); ++i)
            normalAt[i + 1] = normalAt[i] + s.object(i).positions.size();
        normals.resize(normalAt.back());
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
                              normals.begin() + std::ptrdiff_t(normalAt[std::size_t(i)]));
                });
        }
        errors.rethrow();
    }
    for (const Primitive& p : s.primitives) {
        const vec3 base = s.nodes[p.node].base;
        auto eachObject = [&](auto&& f) {
            for (std::size_t i : p.objects) f(i, s.object(i));
        };
        eachObject([&](std::size_t, const ObjectView& o) {
            if (base == vec3(0.0f)) {
                out.write(o.positions.data(), o.positions.size_bytes());
                return;
            }
            out.elements(o.positions.size(), sizeof(vec3),
                         [&](char* dst, std::size_t first, std::size_t n) {
                             for (std::size_t k = 0; k < n; ++k) {
                                 const vec3 v = o.positions[first + k] - base;
                                 std::memcpy(dst + k * sizeof(vec3), &v, sizeof(vec3));
                             }
                         });
        });
        out.pad();
        if (options.normals) {
            eachObject([&](std::size_t i, const ObjectView& o) {
                out.write(normals.data() + normalAt[i], o.positions.size() * sizeof(vec3));
            });
            out.pad();
        }
        if (p.uvs) {
            eachObject([&](std::size_t, const ObjectView& o) {
                out.write(o.uvs.data(), o.uvs.size_bytes());
            });
            out.pad();
        }
        if (options.labels) {
            auto perVertex = [&](auto value) {
                eachObject([&](std::size_t i, const ObjectView& o) {
                    const float v = float(value(i));
                    out.elements(o.positions.size(), sizeof(float),
                                 [&](char* dst, std::size_t, std::size_t n) {
                                     for (std::size_t k = 0; k < n; ++k)
                                         std::memcpy(dst + 4 * k, &v, 4);
                                 });
                });
                out.pad();
            };
            perVertex([&](std::size_t i) { return s.records[i].plant; });
            perVertex([&](std::size_t i) { return s.records[i].id; });
            perVertex([&](std::size_t i) { return s.records[i].organ; });
            perVertex([&](std::size_t i) { return i; });  // the feature: the table row
        }
        std::uint32_t first = 0;
        eachObject([&](std::size_t, const ObjectView& o) {
            out.elements(o.indices.size(), sizeof(std::uint32_t),
                         [&](char* dst, std::size_t at, std::size_t n) {
                             for (std::size_t k = 0; k < n; ++k) {
                                 const std::uint32_t v = first + o.indices[at + k];
                                 std::memcpy(dst + 4 * k, &v, 4);
                             }
                         });
            first += std::uint32_t(o.positions.size());
        });
        out.pad();
    }
    if (s.animated) {  // the frames' keys, laid out with the nodes
        for (std::size_t f = 0; f < s.frames.size(); ++f) {
            const std::vector<FrameKey> keys = frameKeys(s, f);
            for (const FrameKey& k : keys) out.write(&k.time, 4);
            out.pad();
            for (const FrameKey& k : keys) {
                const float scale[3] = {k.scale, k.scale, k.scale};
                out.write(scale, sizeof scale);
            }
            out.pad();
        }
    }
    if (options.labels) {
        auto columnOf = [&](auto get, auto type) {
            using T = decltype(type);
            out.elements(s.records.size(), sizeof(T),
                         [&](char* dst, std::size_t at, std::size_t n) {
                             for (std::size_t k = 0; k < n; ++k) {
                                 const T v = T(get(s.records[at + k]));
                                 std::memcpy(dst + k * sizeof(T), &v, sizeof(T));
                             }
                         });
            out.pad();
        };
        columnOf([](const ObjectRecord& r) { return r.plant; }, std::int32_t{});
        columnOf([](const ObjectRecord& r) { return r.id; }, std::uint32_t{});
        columnOf([](const ObjectRecord& r) { return r.organ; }, std::uint8_t{});
        columnOf([](const ObjectRecord& r) { return r.leaf; }, std::int32_t{});
        columnOf([](const ObjectRecord& r) { return r.shoot; }, std::int32_t{});
        columnOf([](const ObjectRecord& r) { return r.rank; }, std::int32_t{});
        columnOf([](const ObjectRecord& r) { return r.node; }, std::int32_t{});
        columnOf([](const ObjectRecord& r) { return r.age; }, float{});
        for (std::size_t c = 0; c < kOptionalCount; ++c)
            if (s.hasColumn[c])
                columnOf([c](const ObjectRecord& r) { return r.optional[c]; }, float{});
    }
}

}  // namespace

namespace {

void write(Scene& scene, const std::string& path, const GltfOptions& options) {
    if (scene.records.size() >= (std::size_t(1) << 24))
        throw Error("too many objects for float labels in glTF",
                    {.file = path,
                     .value = std::to_string(scene.records.size()),
                     .validRange = "fewer than 16777216 objects"});
    Buffer buffer;
    json doc = document(scene, options, buffer);
    io::AtomicFile file(path);
    ProgressSteps steps(options.progress, "writing glTF", double(buffer.size()));
    if (lowerExtension(path) == ".gltf") {
        std::string bytes;
        Sink sink(nullptr, &bytes, steps);
        writeBinary(scene, options, sink);
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
        writeBinary(scene, options, sink);
    }
    file.commit();
    steps.finish();
}

void checkExtension(const std::string& path) {
    requireOutputFormat(path, {".glb", ".gltf"}, "writeGLTF writes glTF, binary or text");
}

}  // namespace

void writeGLTF(const Context& context, const std::string& path, const GltfOptions& options) {
    checkExtension(path);
    Scene scene = collect({AnimationFrame{&context, 0.0, options.plants}}, options);
    write(scene, path, options);
}

void writeGLTF(const std::vector<AnimationFrame>& frames, const std::string& path,
               const GltfOptions& options, const AnimationOptions& animation) {
    checkExtension(path);
    io::checkAnimation(frames, animation, path);
    Scene scene = collect(frames, options);
    scene.animated = true;
    scene.framesPerSecond = animation.framesPerSecond;
    write(scene, path, options);
}

}  // namespace plantarch
