// Skinned plants in glTF (gltf_skin.h): joints, skins and vertex weights from the skeletons
// the API layer computes (exportSkeletons).
//
// Each joint is a node under its parent joint, the root joint under the plant's node, with
// the translation and rotation that put it where GltfJoint says at bind pose. A plant's
// vertices are written relative to its node (its base), so a joint's inverse bind matrix
// takes them from that frame into the joint's: the joints' world matrices times these give
// the plant as built. The skinned meshes' nodes are roots of the scene, without transforms,
// as the glTF 2.0 spec asks; the world's z-up to y-up turn reaches them through the joints.

#include "scene_io/gltf_skin.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/quaternion.hpp>
#include <numbers>
#include <string>

#include "plantarch/Error.h"

namespace plantarch::gltf {

namespace {

constexpr int kUByte = 5121, kUShort = 5123;

// A vertex's weights as normalized unsigned bytes: each rounded, the largest taking what makes
// the sum exactly 255.
std::array<std::uint8_t, 4> byteWeights(const GltfInfluence& g) {
    if (g.weights[0] == 1.0f) return {255, 0, 0, 0};  // rigid: most vertices
    std::array<int, 4> w{};
    int sum = 0;
    std::size_t largest = 0;
    for (std::size_t i = 0; i < 4; ++i) {
        w[i] = int(std::lround(std::clamp(g.weights[i], 0.0f, 1.0f) * 255.0f));
        sum += w[i];
        if (g.weights[i] > g.weights[largest]) largest = i;
    }
    w[largest] = std::clamp(w[largest] + 255 - sum, 0, 255);
    return {std::uint8_t(w[0]), std::uint8_t(w[1]), std::uint8_t(w[2]), std::uint8_t(w[3])};
}

glm::dquat quaternion(const GltfJoint& j) {
    return glm::dquat(j.rotation[3], j.rotation[0], j.rotation[1], j.rotation[2]);
}

// The binding of object `id` on skeleton `sk` (null: rigid on the root).
const GltfSkinnedObject* bindingOf(const GltfSkeleton& sk, ObjectID id) {
    const auto it =
        std::lower_bound(sk.objects.begin(), sk.objects.end(), id,
                         [](const GltfSkinnedObject& so, ObjectID o) { return so.object < o; });
    return it != sk.objects.end() && it->object == id ? &*it : nullptr;
}

Error badSkeleton(const std::string& path, const GltfSkeleton& sk, const std::string& what,
                  const std::string& value, const std::string& range) {
    return Error("skeleton of plant " + std::to_string(sk.plant) + ": " + what,
                 {.file = path, .parameter = "skeletons", .value = value, .validRange = range});
}

// Every joint and binding usable: parents before children, finite unit rotations, joints in
// range, one influence per vertex, weights non-negative and summing to 1.
void checkSkeleton(const GltfSkeleton& sk, const Scene& s, std::size_t node,
                   const std::string& path) {
    const std::size_t n = sk.joints.size();
    if (n == 0 || n > 65535)
        throw badSkeleton(path, sk, "joint count out of range", std::to_string(n), "1 to 65535");
    for (std::size_t j = 0; j < n; ++j) {
        const GltfJoint& jt = sk.joints[j];
        if (j == 0 ? jt.parent != -1 : jt.parent < 0 || std::size_t(jt.parent) >= j)
            throw badSkeleton(path, sk, "joint " + std::to_string(j) + " has a bad parent",
                              std::to_string(jt.parent),
                              j == 0 ? "-1 (the root)" : "0 to " + std::to_string(j - 1));
        const double length = glm::length(quaternion(jt));
        bool finite = std::isfinite(length) && std::abs(length - 1.0) < 1e-3;
        for (int k = 0; k < 3; ++k) finite = finite && std::isfinite(jt.position[k]);
        if (!finite)
            throw badSkeleton(path, sk, "joint " + std::to_string(j) + " is not finite", jt.name,
                              "a finite position and a unit rotation");
    }
    for (const ObjectRecord& r : s.records) {
        if (r.plant != s.nodes[node].plant) continue;
        const GltfSkinnedObject* so = bindingOf(sk, r.id);
        if (!so) continue;
        if (so->joint >= n)
            throw badSkeleton(path, sk, "object " + std::to_string(r.id) + " names no joint",
                              std::to_string(so->joint), "0 to " + std::to_string(n - 1));
        if (so->vertices.empty()) continue;
        const std::size_t count = s.object(r).positions.size();
        if (so->vertices.size() != count)
            throw badSkeleton(path, sk,
                              "object " + std::to_string(r.id) + " needs one influence per vertex",
                              std::to_string(so->vertices.size()), std::to_string(count));
        for (const GltfInfluence& g : so->vertices) {
            double sum = 0.0;
            bool ok = true;
            for (int i = 0; i < 4; ++i) {
                ok = ok && g.joints[i] < n && std::isfinite(g.weights[i]) && g.weights[i] >= 0.0f;
                sum += g.weights[i];
            }
            if (!ok || std::abs(sum - 1.0) > 1e-5)
                throw badSkeleton(
                    path, sk, "object " + std::to_string(r.id) + " has a bad vertex weight",
                    "sum " + std::to_string(sum),
                    "joints 0 to " + std::to_string(n - 1) + ", weights >= 0 summing to 1");
        }
    }
}

// The wind: key times shared by every joint, 17 over one period (the last the first again).
constexpr int kWindKeys = 17;
constexpr double kWindPeriod = 2.0;  // s

// Adds the wind's channels of one skeleton (joint j's node at first + j) to `animation`,
// starting it (and its key times) when null. A joint at depth k (its root 0) turns about the
// world's y axis through its origin by A k / (1 + 2 + ... + K) sin(2 pi t / T - 0.3 k), K the
// deepest: its subtree's turns add up to about A at the deepest tip, a wave running upward.
void addWind(GltfArrays& d, Buffer& buffer, const GltfSkeleton& sk, std::size_t first,
             float degrees, json& animation, std::size_t& input) {
    if (animation.is_null()) {
        const int times = buffer.add(d.views, kWindKeys * 4, 0, [](Sink& out) {
            writeValues<float>(out, kWindKeys, [](std::size_t k) {
                return float(kWindPeriod * double(k) / double(kWindKeys - 1));
            });
        });
        json keys = accessor(times, kFloat, kWindKeys, "SCALAR");
        keys["min"] = {0.0};
        keys["max"] = {kWindPeriod};
        d.accessors.push_back(std::move(keys));
        input = d.accessors.size() - 1;
        animation = {{"name", "wind"}, {"channels", json::array()}, {"samplers", json::array()}};
    }
    std::vector<int> depth(sk.joints.size(), 0);
    int deepest = 1;
    for (std::size_t j = 1; j < sk.joints.size(); ++j)
        deepest = std::max(deepest, depth[j] = depth[std::size_t(sk.joints[j].parent)] + 1);
    const double sum = 0.5 * double(deepest) * double(deepest + 1);
    const double amplitude = double(degrees) * std::numbers::pi / 180.0 / sum;
    // Each joint's rest rotation (relative to its parent, as its node has it) and, for each
    // key, that rotation followed by the sway about world y seen from the joint.
    const std::size_t joints = sk.joints.size() - 1;
    const int view =
        buffer.add(d.views, joints * kWindKeys * 16, 0, [&sk, depth, amplitude](Sink& out) {
            for (std::size_t j = 1; j < sk.joints.size(); ++j) {
                const GltfJoint& jt = sk.joints[j];
                const glm::dquat world = glm::normalize(quaternion(jt));
                const glm::dquat rest = glm::normalize(
                    glm::conjugate(glm::normalize(quaternion(sk.joints[std::size_t(jt.parent)]))) *
                    world);
                const glm::dvec3 axis = glm::conjugate(world) * glm::dvec3(0.0, 1.0, 0.0);
                for (int k = 0; k < kWindKeys; ++k) {
                    const double t = kWindPeriod * double(k) / double(kWindKeys - 1);
                    const double angle =
                        amplitude * double(depth[j]) *
                        std::sin(2.0 * std::numbers::pi * t / kWindPeriod - 0.3 * double(depth[j]));
                    const glm::dquat q = glm::normalize(rest * glm::angleAxis(angle, axis));
                    const float v[4] = {float(q.x), float(q.y), float(q.z), float(q.w)};
                    out.write(v, 16);
                }
            }
        });
    for (std::size_t j = 1; j < sk.joints.size(); ++j) {
        json output = accessor(view, kFloat, kWindKeys, "VEC4");
        output["byteOffset"] = (j - 1) * kWindKeys * 16;
        d.accessors.push_back(std::move(output));
        json& samplers = animation["samplers"];
        samplers.push_back(
            {{"input", input}, {"output", d.accessors.size() - 1}, {"interpolation", "LINEAR"}});
        animation["channels"].push_back({{"sampler", samplers.size() - 1},
                                         {"target", {{"node", first + j}, {"path", "rotation"}}}});
    }
}

}  // namespace

const GltfSkeleton* skeletonOf(const Scene& s, const GltfOptions& options, std::size_t node) {
    if (s.animated || s.organNodes || s.nodes[node].plant < 0) return nullptr;
    for (const GltfSkeleton& sk : options.skeletons)
        if (sk.plant == s.nodes[node].plant) return &sk;
    return nullptr;
}

void addSkinAttributes(GltfArrays& d, const Scene& s, const GltfOptions& options, Buffer& buffer,
                       const Primitive& p, json& attributes) {
    const GltfSkeleton* sk = skeletonOf(s, options, p.node);
    if (!sk) return;
    // Each object's vertices, on their own joint or blended, in the primitive's order: f(out,
    // first influence, count, blended) writes one object's block.
    auto each = [&s, &p, sk](Sink& out, std::size_t bytes, auto&& write) {
        for (std::size_t i : p.objects) {
            const GltfSkinnedObject* so = bindingOf(*sk, s.records[i].id);
            const std::size_t count = s.object(i).positions.size();
            GltfInfluence rigid;
            rigid.joints[0] = so ? so->joint : 0;
            rigid.weights[0] = 1.0f;
            const bool blended = so && !so->vertices.empty();
            out.elements(count, bytes, [&](char* dst, std::size_t first, std::size_t n) {
                for (std::size_t k = 0; k < n; ++k)
                    write(dst + k * bytes, blended ? so->vertices[first + k] : rigid);
            });
        }
    };
    // Joints as unsigned bytes for up to 256 joints, else shorts; weights as normalized
    // unsigned bytes (a vertex's sum exactly 255: the bind pose is exact whatever the split).
    const bool small = sk->joints.size() <= 256;
    const std::size_t jointBytes = small ? 4 : 8;
    const int joints =
        buffer.add(d.views, p.vertices * jointBytes, kArrayBuffer, [each, small](Sink& out) {
            each(out, small ? 4 : 8, [small](char* dst, const GltfInfluence& g) {
                const std::array<std::uint8_t, 4> w = byteWeights(g);
                for (int i = 0; i < 4; ++i) {
                    const std::uint16_t j = w[std::size_t(i)] ? g.joints[std::size_t(i)] : 0;
                    if (small)
                        dst[i] = char(std::uint8_t(j));
                    else
                        std::memcpy(dst + 2 * i, &j, 2);
                }
            });
        });
    d.accessors.push_back(accessor(joints, small ? kUByte : kUShort, p.vertices, "VEC4"));
    attributes["JOINTS_0"] = d.accessors.size() - 1;
    const int weights = buffer.add(d.views, p.vertices * 4, kArrayBuffer, [each](Sink& out) {
        each(out, 4, [](char* dst, const GltfInfluence& g) {
            const std::array<std::uint8_t, 4> w = byteWeights(g);
            std::memcpy(dst, w.data(), 4);
        });
    });
    json w = accessor(weights, kUByte, p.vertices, "VEC4");
    w["normalized"] = true;
    d.accessors.push_back(std::move(w));
    attributes["WEIGHTS_0"] = d.accessors.size() - 1;
}

void checkSkins(const Scene& s, const GltfOptions& options, const std::string& path) {
    if (!(options.windDegrees >= 0.0f && options.windDegrees <= 90.0f))
        throw Error("the wind's sway out of range", {.file = path,
                                                     .parameter = "wind",
                                                     .value = std::to_string(options.windDegrees),
                                                     .validRange = "0 to 90 degrees"});
    for (std::size_t n = 0; n < s.nodes.size(); ++n)
        if (const GltfSkeleton* sk = skeletonOf(s, options, n)) checkSkeleton(*sk, s, n, path);
}

SkinNodes addSkins(GltfArrays& d, const Scene& s, const GltfOptions& options, Buffer& buffer,
                   const json& plantNodes) {
    SkinNodes out;
    std::size_t windInput = 0;  // the wind's key times, shared by every skeleton
    for (std::size_t n = 0; n < s.nodes.size(); ++n) {
        const GltfSkeleton* sk = skeletonOf(s, options, n);
        if (!sk) continue;
        const std::size_t plantNode = plantNodes.at(n).get<std::size_t>();
        const int skin = int(out.skins.size());
        // The meshes leave the plant's node for the scene's roots.
        json kept = json::array();
        for (const json& child : d.nodes[plantNode].value("children", json::array())) {
            json& c = d.nodes[child.get<std::size_t>()];
            if (!c.contains("mesh")) {
                kept.push_back(child);
                continue;
            }
            if (c.contains("translation") || c.contains("rotation") || c.contains("scale") ||
                c.contains("matrix") || c.contains("children"))
                throw Error("a skinned plant's meshes cannot have transforms of their own",
                            {.parameter = "skeletons",
                             .value = c.value("name", std::string()),
                             .validRange = "plain mesh nodes (one node per organ kind)"});
            c["skin"] = skin;
            out.roots.push_back(child);
        }
        // The joints: node of joint j at first + j, under its parent (the root under the plant).
        const std::size_t first = d.nodes.size();
        const glm::dvec3 base(s.nodes[n].base);
        std::vector<json> children(sk->joints.size(), json::array());
        for (std::size_t j = 1; j < sk->joints.size(); ++j)
            children[std::size_t(sk->joints[j].parent)].push_back(first + j);
        json jointNodes = json::array();
        for (std::size_t j = 0; j < sk->joints.size(); ++j) {
            const GltfJoint& jt = sk->joints[j];
            glm::dvec3 at = glm::dvec3(jt.position) - base;
            glm::dquat turn = quaternion(jt);
            if (jt.parent >= 0) {
                const GltfJoint& up = sk->joints[std::size_t(jt.parent)];
                const glm::dquat inverse = glm::conjugate(quaternion(up));
                at = inverse * (glm::dvec3(jt.position) - glm::dvec3(up.position));
                turn = inverse * turn;
            }
            turn = glm::normalize(turn);
            json node = {
                {"name", jt.name},
                {"translation", {float(at.x), float(at.y), float(at.z)}},
                {"rotation", {float(turn.x), float(turn.y), float(turn.z), float(turn.w)}}};
            if (!children[j].empty()) node["children"] = children[j];
            d.nodes.push_back(std::move(node));
            jointNodes.push_back(first + j);
        }
        kept.push_back(first);
        d.nodes[plantNode]["children"] = kept;  // (after the joints: d.nodes grew)
        // Inverse bind matrices: from the plant node's frame into each joint's, column-major.
        const int view = buffer.add(d.views, sk->joints.size() * 64, 0, [sk, base](Sink& out) {
            for (const GltfJoint& jt : sk->joints) {
                glm::dmat4 bind = glm::dmat4(glm::mat3_cast(quaternion(jt)));
                bind[3] = glm::dvec4(glm::dvec3(jt.position) - base, 1.0);
                const glm::mat4 inverse(glm::affineInverse(bind));
                out.write(&inverse[0][0], 64);
            }
        });
        d.accessors.push_back(accessor(view, kFloat, sk->joints.size(), "MAT4"));
        out.skins.push_back({{"name", "plant_" + std::to_string(sk->plant)},
                             {"inverseBindMatrices", d.accessors.size() - 1},
                             {"skeleton", first},
                             {"joints", jointNodes}});
        if (options.windDegrees > 0.0f)
            addWind(d, buffer, *sk, first, options.windDegrees, out.animation, windInput);
    }
    return out;
}

}  // namespace plantarch::gltf
