#pragma once
// A .glb file taken apart for the glTF tests: its JSON and binary chunk, and the values of
// its accessors and buffer views.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <tuple>
#include <vector>

#include "plantarch/Context.h"

namespace plantarch::testing {

/// A path in the temporary folder for `name`, unique to this process and the running test's
/// suite (plantarch_<suite>_<pid>_<name>).
inline std::filesystem::path tempPath(const std::string& name) {
    const char* suite = ::testing::UnitTest::GetInstance()->current_test_info()->test_suite_name();
    return std::filesystem::temp_directory_path() /
           ("plantarch_" + std::string(suite) + "_" + std::to_string(::getpid()) + "_" + name);
}

inline std::string readAll(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

struct Glb {
    nlohmann::json doc;
    std::string bin;
};

/// The chunks of a .glb, checking its header and chunk types on the way.
inline Glb parseGlb(const std::string& bytes) {
    std::uint32_t header[3], chunk[2];
    EXPECT_GE(bytes.size(), 20u);
    std::memcpy(header, bytes.data(), 12);
    EXPECT_EQ(header[0], 0x46546C67u);  // "glTF"
    EXPECT_EQ(header[1], 2u);
    EXPECT_EQ(header[2], bytes.size());
    std::memcpy(chunk, bytes.data() + 12, 8);
    EXPECT_EQ(chunk[1], 0x4E4F534Au);  // "JSON"
    EXPECT_EQ(chunk[0] % 4, 0u);
    Glb g;
    g.doc = nlohmann::json::parse(bytes.substr(20, chunk[0]));
    const std::size_t binAt = 20 + chunk[0];
    if (binAt == bytes.size()) return g;  // no binary chunk: a scene with no data
    std::memcpy(chunk, bytes.data() + binAt, 8);
    EXPECT_EQ(chunk[1], 0x004E4942u);  // "BIN"
    g.bin = bytes.substr(binAt + 8, chunk[0]);
    return g;
}

/// The values of an accessor (tightly packed, as plantarch writes them, from the accessor's
/// byteOffset in its view; zeros with sparse values laid over them).
template <class T>
std::vector<T> accessorValues(const Glb& g, int accessorIndex) {
    const nlohmann::json& a = g.doc["accessors"][accessorIndex];
    const std::string type = a["type"];
    const std::size_t components = type == "VEC4" ? 4 : type == "VEC3" ? 3 : type == "VEC2" ? 2 : 1;
    std::vector<T> out(a["count"].get<std::size_t>() * components);
    if (a.contains("bufferView")) {
        const nlohmann::json& v = g.doc["bufferViews"][a["bufferView"].get<int>()];
        std::memcpy(out.data(),
                    g.bin.data() + v["byteOffset"].get<std::size_t>() +
                        a.value("byteOffset", std::size_t(0)),
                    out.size() * sizeof(T));
    }
    if (a.contains("sparse")) {
        const nlohmann::json& s = a["sparse"];
        const std::size_t n = s["count"];
        EXPECT_EQ(s["indices"]["componentType"], 5125);  // plantarch writes uint32 indices
        const nlohmann::json& iv = g.doc["bufferViews"][s["indices"]["bufferView"].get<int>()];
        const nlohmann::json& vv = g.doc["bufferViews"][s["values"]["bufferView"].get<int>()];
        std::vector<std::uint32_t> indices(n);
        std::memcpy(indices.data(), g.bin.data() + iv["byteOffset"].get<std::size_t>(), 4 * n);
        for (std::size_t k = 0; k < n; ++k)
            std::memcpy(
                out.data() + indices[k] * components,
                g.bin.data() + vv["byteOffset"].get<std::size_t>() + k * components * sizeof(T),
                components * sizeof(T));
    }
    return out;
}

/// The first `count` values of a buffer view.
template <class T>
std::vector<T> viewValues(const Glb& g, int view, std::size_t count) {
    const nlohmann::json& v = g.doc["bufferViews"][view];
    std::vector<T> out(count);
    std::memcpy(out.data(), g.bin.data() + v["byteOffset"].get<std::size_t>(), count * sizeof(T));
    return out;
}

// ---- files with a node per organ ----

using json = nlohmann::json;
using glm::mat4;
using glm::vec3;

/// An organ as the test names it: organ, shoot, node, leaf and its ordinal among organs with
/// the same four.
using OrganKey = std::tuple<std::string, int, int, int, int>;

/// Each organ's vertices in a Context, keyed as shownAt keys them (labels from the objects'
/// data, the ordinal in ID order).
inline std::map<OrganKey, std::vector<vec3>> organVertices(const Context& ctx) {
    std::map<OrganKey, std::vector<vec3>> out;
    std::map<std::tuple<std::string, int, int, int>, int> ordinals;
    for (ObjectID id : ctx.objectIDs()) {
        const std::string organ = ctx.objectDataString(id, "organ").value_or("");
        const int shoot = ctx.objectDataInt(id, "shootID").value_or(-1);
        const int node = ctx.objectDataInt(id, "node").value_or(-1);
        const int leaf = ctx.objectDataInt(id, "leafID").value_or(-1);
        const int ordinal = ordinals[{organ, shoot, node, leaf}]++;
        const ObjectView o = ctx.object(id);
        out[{organ, shoot, node, leaf, ordinal}].assign(o.positions.begin(), o.positions.end());
    }
    return out;
}

/// Whether every organ of `expected` is shown, vertex for vertex, within the writers'
/// tolerance: 1e-5 of the organ's size and a few float steps of its coordinates.
inline ::testing::AssertionResult sameOrgans(
    const std::map<OrganKey, std::vector<vec3>>& shown,
    const std::map<OrganKey, std::vector<vec3>>& expected) {
    if (shown.size() != expected.size())
        return ::testing::AssertionFailure()
               << shown.size() << " organs shown, " << expected.size() << " expected";
    for (const auto& [key, vertices] : expected) {
        const auto at = shown.find(key);
        if (at == shown.end() || at->second.size() != vertices.size())
            return ::testing::AssertionFailure()
                   << "organ " << std::get<0>(key) << " shoot " << std::get<1>(key) << " node "
                   << std::get<2>(key) << " missing or of another size";
        vec3 lo(1e30f), hi(-1e30f);
        for (const vec3& v : vertices) {
            lo = glm::min(lo, v);
            hi = glm::max(hi, v);
        }
        const float extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
        for (std::size_t i = 0; i < vertices.size(); ++i) {
            const vec3 d = glm::abs(at->second[i] - vertices[i]);
            const float reach = std::max(
                {std::abs(vertices[i].x), std::abs(vertices[i].y), std::abs(vertices[i].z)});
            if (std::max({d.x, d.y, d.z}) > 1e-5f * extent + 4e-6f * reach + 1e-6f)
                return ::testing::AssertionFailure()
                       << "organ " << std::get<0>(key) << " shoot " << std::get<1>(key) << " node "
                       << std::get<2>(key) << " vertex " << i << " off by "
                       << std::max({d.x, d.y, d.z});
        }
    }
    return ::testing::AssertionSuccess();
}

// The value a STEP sampler holds at key `k` (the frames' keys are the sampler's inputs).
inline std::vector<float> keyValue(const Glb& g, const json& sampler, std::size_t k,
                                   std::size_t n) {
    const auto values = accessorValues<float>(g, sampler["output"]);
    return std::vector<float>(values.begin() + std::ptrdiff_t(k * n),
                              values.begin() + std::ptrdiff_t((k + 1) * n));
}

/// The organs a node with EXT_mesh_gpu_instancing draws (under `parent`), keyed by their
/// labels as instances: the node's organ, the instance's _SHOOT, _NODE and _LEAF attributes and
/// the ordinal in its name (extras "instances").
inline void instances(const Glb& g, const json& node, const mat4& parent,
                      std::map<OrganKey, std::vector<vec3>>& out) {
    const json& a = node["extensions"]["EXT_mesh_gpu_instancing"]["attributes"];
    const auto t = accessorValues<float>(g, a["TRANSLATION"]);
    const auto r = accessorValues<float>(g, a["ROTATION"]);
    const auto s = accessorValues<float>(g, a["SCALE"]);
    const auto shoot = accessorValues<float>(g, a["_SHOOT"]);
    const auto nodeOf = accessorValues<float>(g, a["_NODE"]);
    const auto leaf = accessorValues<float>(g, a["_LEAF"]);
    const json& p = g.doc["meshes"][node["mesh"].get<std::size_t>()]["primitives"][0];
    const std::vector<float> positions = accessorValues<float>(g, p["attributes"]["POSITION"]);
    const json& names = node["extras"]["instances"];
    EXPECT_EQ(names.size(), shoot.size());
    for (std::size_t i = 0; i < shoot.size(); ++i) {
        const mat4 m =
            parent * glm::translate(mat4(1.0f), vec3(t[3 * i], t[3 * i + 1], t[3 * i + 2])) *
            glm::mat4_cast(glm::quat(r[4 * i + 3], r[4 * i], r[4 * i + 1], r[4 * i + 2])) *
            glm::scale(mat4(1.0f), vec3(s[3 * i], s[3 * i + 1], s[3 * i + 2]));
        const std::string name = names[i];
        const std::string last = name.substr(name.rfind('_') + 1);
        const bool numbered = std::all_of(last.begin(), last.end(), ::isdigit);
        const OrganKey key = {node["extras"]["organ"], int(shoot[i]), int(nodeOf[i]), int(leaf[i]),
                              numbered ? std::stoi(last) - 1 : 0};
        std::vector<vec3>& v = out[key];  // several plants: appended in plant order
        for (std::size_t j = 0; j < positions.size(); j += 3)
            v.push_back(
                vec3(m * glm::vec4(positions[j], positions[j + 1], positions[j + 2], 1.0f)));
    }
}

/// Each organ's vertices of a file with a node per organ (plantarch's z-up axes: under the
/// root's turn) at frame `k` of its animation (or as it stands), from the nodes' transforms,
/// the channels keyed at k, morph targets and the shape nodes' scales; instances of
/// EXT_mesh_gpu_instancing nodes by their instance transforms.
inline std::map<OrganKey, std::vector<vec3>> shownAt(const Glb& g, std::size_t k = 0) {
    const json& nodes = g.doc["nodes"];
    std::map<std::pair<std::size_t, std::string>, const json*> channels;
    if (g.doc.contains("animations")) {
        const json& animation = g.doc["animations"][0];
        for (const json& c : animation["channels"])
            channels[{c["target"]["node"].get<std::size_t>(), c["target"]["path"]}] =
                &animation["samplers"][c["sampler"].get<std::size_t>()];
    }
    auto property = [&](std::size_t node, const char* path, std::size_t n,
                        std::vector<float> value) {
        const auto at = channels.find({node, path});
        if (at != channels.end()) return keyValue(g, *at->second, k, n);
        if (nodes[node].contains(path)) return nodes[node][path].get<std::vector<float>>();
        return value;
    };
    std::map<OrganKey, std::vector<vec3>> out;
    // The organ a node draws: its own labels, or its organ node's for a shape node.
    std::function<void(std::size_t, const mat4&, OrganKey)> visit = [&](std::size_t n,
                                                                        const mat4& parent,
                                                                        OrganKey organ) {
        const std::vector<float> t = property(n, "translation", 3, {0, 0, 0});
        const std::vector<float> r = property(n, "rotation", 4, {0, 0, 0, 1});
        const std::vector<float> s = property(n, "scale", 3, {1, 1, 1});
        if (s[0] == 0.0f) return;  // not shown
        const mat4 m = parent * glm::translate(mat4(1.0f), vec3(t[0], t[1], t[2])) *
                       glm::mat4_cast(glm::quat(r[3], r[0], r[1], r[2])) *
                       glm::scale(mat4(1.0f), vec3(s[0], s[1], s[2]));
        const json& node = nodes[n];
        if (node.contains("extras") && node["extras"].contains("objectID")) {
            const json& l = node["extras"];
            const std::string name = node["name"];
            const std::string last = name.substr(name.rfind('_') + 1);
            const bool numbered = std::all_of(last.begin(), last.end(), ::isdigit);
            organ = {l["organ"], l["shoot"], l["node"], l["leaf"],
                     numbered ? std::stoi(last) - 1 : 0};
        }
        if (node.contains("extensions") && node["extensions"].contains("EXT_mesh_gpu_instancing")) {
            instances(g, node, m, out);
        } else if (node.contains("mesh")) {
            const json& mesh = g.doc["meshes"][node["mesh"].get<std::size_t>()];
            const json& p = mesh["primitives"][0];
            std::vector<float> positions = accessorValues<float>(g, p["attributes"]["POSITION"]);
            if (p.contains("targets")) {
                const std::vector<float> w =
                    property(n, "weights", p["targets"].size(), mesh["weights"]);
                for (std::size_t i = 0; i < w.size(); ++i) {
                    if (w[i] == 0.0f) continue;
                    const auto d = accessorValues<float>(g, p["targets"][i]["POSITION"]);
                    for (std::size_t j = 0; j < d.size(); ++j) positions[j] += w[i] * d[j];
                }
            }
            std::vector<vec3>& v = out[organ];
            for (std::size_t i = 0; i < positions.size(); i += 3)
                v.push_back(
                    vec3(m * glm::vec4(positions[i], positions[i + 1], positions[i + 2], 1.0f)));
        }
        if (node.contains("children"))
            for (const json& c : node["children"]) visit(c.get<std::size_t>(), m, organ);
    };
    const json& root = nodes[g.doc["scenes"][0]["nodes"][0].get<std::size_t>()];
    for (const json& c : root["children"]) visit(c.get<std::size_t>(), mat4(1.0f), {});
    return out;
}

}  // namespace plantarch::testing
