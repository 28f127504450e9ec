// glTF 2.0 reader for meshes: binary .glb files and .gltf files whose buffers are embedded,
// plantarch's own with their per-vertex labels and other tools' triangle meshes. Everything is
// parsed and checked before the Context is touched, so a bad file leaves it unchanged.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "core/input_file.h"
#include "plantarch/Error.h"
#include "plantarch/Export.h"
#include "plantarch/OutputFormats.h"
#include "scene_io/gltf_lod.h"

namespace plantarch {

namespace {

using json = nlohmann::json;

inline constexpr io::InputKind kGltfFile{"glTF file", 4096 * io::kMiB, false};
constexpr int kMaxJsonDepth = 64;
constexpr int kMaxNodeDepth = 256;

// Base64 (RFC 4648) of a data URI, or an error.
std::string fromBase64(std::string_view text, const std::string& path) {
    auto value = [](char c) -> int {
        if (c >= 'A' && c <= 'Z') return c - 'A';
        if (c >= 'a' && c <= 'z') return c - 'a' + 26;
        if (c >= '0' && c <= '9') return c - '0' + 52;
        if (c == '+') return 62;
        if (c == '/') return 63;
        return -1;
    };
    std::string out;
    out.reserve(text.size() / 4 * 3);
    std::uint32_t bits = 0;
    int n = 0;
    for (char c : text) {
        if (c == '=') break;
        const int v = value(c);
        if (v < 0) throw Error("a buffer's data URI is not base64", {.file = path});
        bits = (bits << 6) | std::uint32_t(v);
        if (++n == 4) {
            out += char((bits >> 16) & 0xFF);
            out += char((bits >> 8) & 0xFF);
            out += char(bits & 0xFF);
            bits = 0;
            n = 0;
        }
    }
    if (n == 2) out += char((bits >> 4) & 0xFF);
    if (n == 3) {
        out += char((bits >> 10) & 0xFF);
        out += char((bits >> 2) & 0xFF);
    }
    return out;
}

class Document {
public:
    Document(const std::string& bytes, const std::string& path, bool binary) : path_(path) {
        std::string_view text = bytes;
        std::string bin;
        if (binary) {
            if (bytes.size() < 20 || bytes.compare(0, 4, "glTF") != 0)
                fail("not a binary glTF file: it does not start with \"glTF\"");
            const std::uint32_t version = u32(bytes, 4), length = u32(bytes, 8);
            if (version != 2) fail("glTF version " + std::to_string(version) + " (valid: 2)");
            if (length > bytes.size()) fail("the file ends before its declared length");
            const std::uint32_t jsonLength = u32(bytes, 12);
            if (u32(bytes, 16) != 0x4E4F534Au || jsonLength > length - 20)
                fail("the first chunk is not a JSON chunk that fits the file");
            text = std::string_view(bytes).substr(20, jsonLength);
            const std::size_t next = 20 + std::size_t(jsonLength);
            if (next + 8 <= length && u32(bytes, next + 4) == 0x004E4942u) {
                const std::uint32_t binLength = u32(bytes, next);
                if (binLength > length - next - 8) fail("the binary chunk does not fit the file");
                bin = bytes.substr(next + 8, binLength);
            }
        }
        int depth = 0;
        const auto limitDepth = [&](int d, json::parse_event_t, json&) {
            depth = std::max(depth, d);
            if (d > kMaxJsonDepth)
                throw Error("the JSON is nested too deeply",
                            {.file = path_, .validRange = "at most 64 levels"});
            return true;
        };
        try {
            doc_ = json::parse(text.begin(), text.end(), limitDepth);
        } catch (const json::exception& e) {
            fail(std::string("not JSON: ") + e.what());
        }
        if (!doc_.is_object()) fail("the JSON is not an object");
        for (const json& b : array("buffers")) {
            if (!b.is_object()) fail("a buffer is not an object");
            if (!b.contains("uri")) {
                buffers_.push_back(bin);
                continue;
            }
            const std::string uri = b.value("uri", std::string());
            const std::size_t comma = uri.find(',');
            if (uri.rfind("data:", 0) != 0 || comma == std::string::npos ||
                uri.compare(comma - 7, 7, ";base64") != 0)
                fail("buffer \"" + uri.substr(0, 40) +
                     "\" is a separate file, which is not read: write the scene as .glb");
            buffers_.push_back(fromBase64(std::string_view(uri).substr(comma + 1), path_));
        }
        gltf::decodeMeshopt(doc_, buffers_, path_);  // EXT_meshopt_compression (gltf_lod.cpp)
    }

    const json& doc() const { return doc_; }

    const json& array(const char* name) const {
        static const json empty = json::array();
        const auto it = doc_.find(name);
        if (it == doc_.end()) return empty;
        if (!it->is_array()) fail(std::string("\"") + name + "\" is not a list");
        return *it;
    }

    // Element `index` of the top-level list `name`, checked.
    const json& at(const char* name, const json& index) const {
        const json& list = array(name);
        if (!index.is_number_unsigned() || index.get<std::uint64_t>() >= list.size())
            fail(std::string("a reference into \"") + name + "\" is out of range");
        const json& item = list[index.get<std::size_t>()];
        if (!item.is_object()) fail(std::string("an entry of \"") + name + "\" is not an object");
        return item;
    }

    // The values of a SCALAR, VEC3 or VEC4 accessor as doubles (components in order).
    std::vector<double> accessor(const json& index, const char* type, bool indices) const {
        const json& a = at("accessors", index);
        const std::uint64_t count = number(a, "count");
        const int componentType = int(number(a, "componentType"));
        if (a.value("type", std::string()) != type)
            fail(std::string("an accessor is not of type ") + type);
        const int components = std::string_view(type) == "VEC3"   ? 3
                               : std::string_view(type) == "VEC4" ? 4
                                                                  : 1;
        std::size_t size = 0;
        switch (componentType) {
            case 5121:
                size = 1;
                break;
            case 5123:
                size = 2;
                break;
            case 5125:
            case 5126:
                size = 4;
                break;
            default:
                fail("accessor component type " + std::to_string(componentType) +
                     " (valid: 5121, 5123, 5125 unsigned integers, 5126 float)");
        }
        if (indices == (componentType == 5126)) fail("an accessor has the wrong component type");
        if (!a.contains("bufferView")) fail("an accessor has no buffer view");
        const json& view = at("bufferViews", a["bufferView"]);
        const std::uint64_t buffer = number(view, "buffer");
        if (buffer >= buffers_.size()) fail("a buffer view names no buffer");
        const std::string& data = buffers_[std::size_t(buffer)];
        const std::uint64_t viewOffset =
            view.contains("byteOffset") ? number(view, "byteOffset") : 0;
        const std::uint64_t viewLength = number(view, "byteLength");
        const std::uint64_t offset = a.contains("byteOffset") ? number(a, "byteOffset") : 0;
        const std::uint64_t element = size * std::uint64_t(components);
        const std::uint64_t stride =
            view.contains("byteStride") ? number(view, "byteStride") : element;
        if (stride < element || viewOffset > data.size() || viewLength > data.size() - viewOffset)
            fail("a buffer view reaches past its buffer");
        if (count > 0) {
            if (offset > viewLength || viewLength - offset < element ||
                count - 1 > (viewLength - offset - element) / stride)
                fail("an accessor reaches past its buffer view");
        }
        std::vector<double> out;
        out.reserve(std::size_t(count * std::uint64_t(components)));
        for (std::uint64_t i = 0; i < count; ++i) {
            const char* p = data.data() + viewOffset + offset + i * stride;
            for (int c = 0; c < components; ++c, p += size) {
                switch (componentType) {
                    case 5121:
                        out.push_back(double(static_cast<unsigned char>(*p)));
                        break;
                    case 5123: {
                        std::uint16_t v;
                        std::memcpy(&v, p, 2);
                        out.push_back(double(v));
                        break;
                    }
                    case 5125: {
                        std::uint32_t v;
                        std::memcpy(&v, p, 4);
                        out.push_back(double(v));
                        break;
                    }
                    default: {
                        float v;
                        std::memcpy(&v, p, 4);
                        out.push_back(double(v));
                    }
                }
            }
        }
        return out;
    }

    std::uint64_t number(const json& object, const char* key) const {
        const auto it = object.find(key);
        if (it == object.end() || !it->is_number_unsigned())
            fail(std::string("\"") + key + "\" is missing or not a whole number >= 0");
        return it->get<std::uint64_t>();
    }

    [[noreturn]] void fail(const std::string& what) const { throw Error(what, {.file = path_}); }

private:
    static std::uint32_t u32(const std::string& b, std::size_t at) {
        std::uint32_t v;
        std::memcpy(&v, b.data() + at, 4);
        return v;  // glTF is little-endian, as every machine plantarch builds on
    }

    std::string path_;
    json doc_;
    std::vector<std::string> buffers_;
};

// A node's local transform (matrix, or translation, rotation and scale).
glm::dmat4 localTransform(const json& node, const Document& d) {
    auto numbers = [&](const char* key, std::size_t n) {
        std::vector<double> v;
        const auto it = node.find(key);
        if (it == node.end()) return v;
        if (!it->is_array() || it->size() != n)
            d.fail(std::string("a node's ") + key + " is malformed");
        for (const json& x : *it) {
            if (!x.is_number() || !std::isfinite(x.get<double>()))
                d.fail(std::string("a node's ") + key + " is not finite numbers");
            v.push_back(x.get<double>());
        }
        return v;
    };
    glm::dmat4 m(1.0);
    if (const std::vector<double> mat = numbers("matrix", 16); !mat.empty()) {
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) m[c][r] = mat[std::size_t(c * 4 + r)];
        return m;
    }
    if (const auto t = numbers("translation", 3); !t.empty())
        m = glm::translate(m, glm::dvec3(t[0], t[1], t[2]));
    if (const auto q = numbers("rotation", 4); !q.empty())
        m = m * glm::mat4_cast(glm::dquat(q[3], q[0], q[1], q[2]));
    if (const auto s = numbers("scale", 3); !s.empty())
        m = glm::scale(m, glm::dvec3(s[0], s[1], s[2]));
    return m;
}

// The instance transforms of a node with EXT_mesh_gpu_instancing (each instance's translation,
// rotation and scale, applied before the node's transform); one identity without it.
std::vector<glm::dmat4> instanceTransforms(const json& node, const Document& d) {
    const auto ext = node.find("extensions");
    if (ext == node.end() || !ext->is_object() || !ext->contains("EXT_mesh_gpu_instancing"))
        return {glm::dmat4(1.0)};
    const json& e = (*ext)["EXT_mesh_gpu_instancing"];
    if (!e.is_object() || !e.contains("attributes") || !e["attributes"].is_object())
        d.fail("EXT_mesh_gpu_instancing has no attributes");
    const json& a = e["attributes"];
    auto values = [&](const char* name, const char* type) {
        std::vector<double> v;
        if (a.contains(name)) v = d.accessor(a[name], type, false);
        for (double x : v)
            if (!std::isfinite(x)) d.fail("EXT_mesh_gpu_instancing: an instance is not finite");
        return v;
    };
    const std::vector<double> t = values("TRANSLATION", "VEC3"), r = values("ROTATION", "VEC4"),
                              s = values("SCALE", "VEC3");
    const std::size_t count = std::max({t.size() / 3, r.size() / 4, s.size() / 3});
    if ((!t.empty() && t.size() != 3 * count) || (!r.empty() && r.size() != 4 * count) ||
        (!s.empty() && s.size() != 3 * count))
        d.fail("EXT_mesh_gpu_instancing: attributes of different counts");
    std::vector<glm::dmat4> out;
    for (std::size_t i = 0; i < count; ++i) {
        glm::dmat4 m(1.0);
        if (!t.empty()) m = glm::translate(m, glm::dvec3(t[3 * i], t[3 * i + 1], t[3 * i + 2]));
        if (!r.empty())
            m = m * glm::mat4_cast(glm::dquat(r[4 * i + 3], r[4 * i], r[4 * i + 1], r[4 * i + 2]));
        if (!s.empty()) m = glm::scale(m, glm::dvec3(s[3 * i], s[3 * i + 1], s[3 * i + 2]));
        out.push_back(m);
    }
    return out;
}

// A label value as a whole number (-1 for one that is not: NaN, huge, negative).
int labelNumber(double v) {
    return v >= 0.0 && v <= 2147483647.0 ? int(v) : -1;
}

struct Part {
    Mesh mesh;
    int plant = -1;
    int organ = 0;
};

}  // namespace

std::vector<ObjectID> readGLTF(Context& context, const std::string& path) {
    const std::string ext = lowerExtension(path);
    if (ext != ".glb" && ext != ".gltf")
        throw Error("a glTF scene is read from .glb or .gltf",
                    {.file = path, .value = ext, .validRange = ".glb, .gltf"});
    io::InputFile file(path, kGltfFile);
    const Document d(file.readAll(), path, ext == ".glb");
    const json& doc = d.doc();

    // The meshes of the default scene's nodes, with their world transforms.
    std::vector<std::pair<const json*, glm::dmat4>> placed;
    std::vector<char> visiting(d.array("nodes").size(), 0);
    auto visit = [&](auto&& self, const json& index, const glm::dmat4& parent, int depth) -> void {
        const json& node = d.at("nodes", index);
        const std::size_t i = index.get<std::size_t>();
        if (visiting[i] || depth > kMaxNodeDepth)
            d.fail("the node hierarchy has a cycle or is too deep");
        visiting[i] = 1;
        const glm::dmat4 world = parent * localTransform(node, d);
        if (node.contains("mesh"))  // once per instance with EXT_mesh_gpu_instancing
            for (const glm::dmat4& instance : instanceTransforms(node, d))
                placed.emplace_back(&d.at("meshes", node["mesh"]), world * instance);
        if (const auto c = node.find("children"); c != node.end()) {
            if (!c->is_array()) d.fail("a node's children are not a list");
            for (const json& child : *c) self(self, child, world, depth + 1);
        }
        visiting[i] = 0;
    };
    const json& scenes = d.array("scenes");
    if (!scenes.empty()) {
        const json& scene = d.at("scenes", doc.contains("scene") ? doc["scene"] : json(0));
        if (const auto roots = scene.find("nodes"); roots != scene.end() && roots->is_array())
            for (const json& root : *roots) visit(visit, root, glm::dmat4(1.0), 0);
    }

    // glTF's y up becomes plantarch's z up.
    const glm::dmat4 zUp(1, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1);
    std::vector<Part> parts;
    std::map<long long, std::size_t> partOf;  // _OBJECT_ID -> part
    for (const auto& [mesh, world] : placed) {
        const auto prims = mesh->find("primitives");
        if (prims == mesh->end() || !prims->is_array()) d.fail("a mesh has no primitives list");
        for (const json& prim : *prims) {
            if (!prim.is_object() || prim.value("mode", 4) != 4) continue;  // triangles only
            const auto attributes = prim.find("attributes");
            if (attributes == prim.end() || !attributes->contains("POSITION"))
                d.fail("a primitive has no POSITION");
            const std::vector<double> xyz = d.accessor((*attributes)["POSITION"], "VEC3", false);
            const std::size_t n = xyz.size() / 3;
            auto label = [&](const char* name) {
                return attributes->contains(name) ? d.accessor((*attributes)[name], "SCALAR", false)
                                                  : std::vector<double>();
            };
            const std::vector<double> objects = label("_OBJECT_ID"), plants = label("_PLANT_ID"),
                                      organs = label("_ORGAN");
            for (const auto* v : {&objects, &plants, &organs})
                if (!v->empty() && v->size() != n) d.fail("a label attribute's count differs");
            std::vector<double> corners;
            if (prim.contains("indices")) {
                corners = d.accessor(prim["indices"], "SCALAR", true);
            } else {
                for (std::size_t i = 0; i < n; ++i) corners.push_back(double(i));
            }
            if (corners.size() % 3) d.fail("a primitive's corner count is not a multiple of 3");
            const glm::dmat4 m = zUp * world;
            const std::size_t fresh = parts.size();
            std::map<std::uint32_t, std::pair<std::size_t, std::uint32_t>> local;
            for (std::size_t t = 0; t < corners.size(); t += 3) {
                if (!(corners[t] < double(n))) d.fail("a corner index is out of range");
                const auto first = std::size_t(corners[t]);
                const long long key = objects.empty() ? -1 - (long long)fresh
                                                      : (long long)labelNumber(objects[first]);
                auto [it, added] = partOf.emplace(key, parts.size());
                if (added) {
                    Part p;
                    if (!plants.empty()) p.plant = labelNumber(plants[first]);
                    if (!organs.empty()) p.organ = labelNumber(organs[first]);
                    parts.push_back(std::move(p));
                }
                Part& part = parts[it->second];
                for (std::size_t k = 0; k < 3; ++k) {
                    const double c = corners[t + k];
                    if (!(c < double(n))) d.fail("a corner index is out of range");
                    const auto ci = std::uint32_t(c);
                    auto [at, isNew] = local.emplace(
                        ci, std::make_pair(it->second, std::uint32_t(part.mesh.positions.size())));
                    if (isNew || at->second.first != it->second) {
                        const glm::dvec4 q =
                            m * glm::dvec4(xyz[3 * ci], xyz[3 * ci + 1], xyz[3 * ci + 2], 1.0);
                        for (int a = 0; a < 3; ++a)
                            if (!(std::abs(q[a]) <= double(std::numeric_limits<float>::max())))
                                d.fail("a vertex is not a finite float");
                        at->second = {it->second, std::uint32_t(part.mesh.positions.size())};
                        part.mesh.positions.push_back(vec3(float(q.x), float(q.y), float(q.z)));
                    }
                    part.mesh.indices.push_back(at->second.second);
                }
            }
        }
    }
    if (parts.empty()) d.fail("no triangles: render needs a mesh");

    // Objects in ascending _OBJECT_ID (a file plantarch wrote groups them by plant and organ
    // kind: they come back in the order they had), then the primitives without one in file
    // order.
    std::vector<std::size_t> order, unlabelled;
    for (const auto& [key, part] : partOf) (key >= 0 ? order : unlabelled).push_back(part);
    std::sort(unlabelled.begin(), unlabelled.end());  // parts are numbered in file order
    order.insert(order.end(), unlabelled.begin(), unlabelled.end());
    std::vector<ObjectID> made;
    try {
        for (std::size_t k : order) {
            const Part& part = parts[k];
            const ObjectID id = context.addObject(part.mesh);
            made.push_back(id);
            if (part.plant >= 0) context.setObjectData(id, "plantID", std::int32_t(part.plant));
            if (part.organ > 0 && std::size_t(part.organ) < kOrganLabels.size())
                context.setObjectData(id, "organ",
                                      std::string(kOrganLabels[std::size_t(part.organ)]));
        }
    } catch (...) {
        context.deleteObjects(made);
        throw;
    }
    return made;
}

}  // namespace plantarch
