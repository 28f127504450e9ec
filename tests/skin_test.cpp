// A wind-ready skeleton (plantarch/ExportPlants.h exportSkeletons, GltfOptions::skeletons):
// one joint per internode, weights that sum to 1, the bind pose that reproduces the plant,
// bending that poses it, skinned glTF and USD files, determinism and hostile inputs.

#include <gtest/gtest.h>
#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <glm/gtc/quaternion.hpp>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.h"
#include "error_of.h"
#include "glb_reader.h"
#include "plantarch/Bending.h"
#include "plantarch/Error.h"
#include "plantarch/ExportPlants.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;
namespace fs = std::filesystem;
using json = nlohmann::json;
using plantarch::testing::errorOf;
using plantarch::testing::Glb;
using plantarch::testing::parseGlb;
using plantarch::testing::readAll;
using plantarch::testing::tempPath;

namespace {

// A joint's bind matrix (joint space to world), in double.
glm::dmat4 jointMatrix(const GltfJoint& j) {
    const glm::dquat q(j.rotation[3], j.rotation[0], j.rotation[1], j.rotation[2]);
    glm::dmat4 m = glm::dmat4(glm::mat3_cast(q));
    m[3] = glm::dvec4(glm::dvec3(j.position), 1.0);
    return m;
}

std::size_t internodes(const PlantInstance& p) {
    std::size_t n = 0;
    for (const Shoot& s : p.shoots)
        if (!s.removed) n += s.phytomers.size();
    return n;
}

struct Built {
    Context ctx;
    PlantArchitecture arch{&ctx};
    unsigned plant = 0;
    Built(const char* species, float age, bool mechanics = false) {
        arch.loadPlantModelFromLibrary(species);
        plant = arch.buildPlantInstanceFromLibrary({0.5f, -0.25f, 0.0f}, age);
        PhenologyParameters ph = arch.plant(plant).phenology;
        if (ph.mechanics.enabled != mechanics) {
            ph.mechanics.enabled = mechanics;
            arch.setPlantPhenologicalThresholds(plant, ph);
        }
    }
};

// The world position of every vertex of every object skinned with joints posed at `posed`
// (bind pose `bind`, same joints): linear blend skinning.
using Positions = std::map<ObjectID, std::vector<vec3>>;

Positions positionsOf(const Context& ctx, const std::vector<ObjectID>& objects) {
    Positions out;
    for (ObjectID o : objects) {
        const auto p = ctx.object(o).positions;
        out[o].assign(p.begin(), p.end());
    }
    return out;
}

std::map<ObjectID, std::vector<glm::dvec3>> skinned(const Positions& bindPositions,
                                                    const GltfSkeleton& bind,
                                                    const GltfSkeleton& posed) {
    std::vector<glm::dmat4> m;
    for (std::size_t j = 0; j < bind.joints.size(); ++j)
        m.push_back(jointMatrix(posed.joints[j]) * glm::inverse(jointMatrix(bind.joints[j])));
    std::map<ObjectID, const GltfSkinnedObject*> of;
    for (const GltfSkinnedObject& so : bind.objects) of[so.object] = &so;
    std::map<ObjectID, std::vector<glm::dvec3>> out;
    for (const auto& [o, positions] : bindPositions) {
        const auto it = of.find(o);
        std::vector<glm::dvec3>& to = out[o];
        for (std::size_t k = 0; k < positions.size(); ++k) {
            const glm::dvec4 p(glm::dvec3(positions[k]), 1.0);
            glm::dvec4 sum(0.0);
            if (it == of.end()) {
                sum = m[0] * p;
            } else if (it->second->vertices.empty()) {
                sum = m[it->second->joint] * p;
            } else {
                const GltfInfluence& g = it->second->vertices[k];
                for (int i = 0; i < 4; ++i) sum += double(g.weights[i]) * (m[g.joints[i]] * p);
            }
            to.push_back(glm::dvec3(sum));
        }
    }
    return out;
}

}  // namespace

TEST(Skin, OneJointPerInternode) {
    Built b("bean", 40.0f);
    const std::vector<GltfSkeleton> skeletons = exportSkeletons(b.arch);
    ASSERT_EQ(skeletons.size(), 1u);
    const GltfSkeleton& sk = skeletons[0];
    EXPECT_EQ(sk.plant, std::int32_t(b.plant));
    EXPECT_EQ(sk.joints.size(), 1 + internodes(b.arch.plant(b.plant)));
    EXPECT_EQ(sk.joints[0].parent, -1);
    EXPECT_EQ(sk.joints[0].position, b.arch.getPlantBasePosition(b.plant));
    for (std::size_t j = 1; j < sk.joints.size(); ++j) {
        const GltfJoint& jt = sk.joints[j];
        ASSERT_GE(jt.parent, 0);
        ASSERT_LT(std::size_t(jt.parent), j);
        const float n =
            std::sqrt(jt.rotation[0] * jt.rotation[0] + jt.rotation[1] * jt.rotation[1] +
                      jt.rotation[2] * jt.rotation[2] + jt.rotation[3] * jt.rotation[3]);
        EXPECT_NEAR(n, 1.0f, 1e-5f);
        // At its internode's base, its +y along the internode.
        const std::vector<vec3> nodes = bentNodePositions(b.arch, b.plant, unsigned(jt.shoot));
        EXPECT_EQ(jt.position, nodes[std::size_t(jt.node)]);
        const vec3 span = nodes[std::size_t(jt.node) + 1] - jt.position;
        if (glm::length(span) > 1e-6f) {
            const glm::dvec3 y = jointMatrix(jt)[1];
            EXPECT_NEAR(glm::dot(y, glm::dvec3(glm::normalize(span))), 1.0, 1e-5);
        }
    }
}

TEST(Skin, WeightsAreNonNegativeAndSumToOne) {
    Built b("bean", 40.0f);
    const GltfSkeleton sk = exportSkeletons(b.arch).at(0);
    std::size_t blended = 0;
    ObjectID last = 0;
    for (const GltfSkinnedObject& so : sk.objects) {
        EXPECT_TRUE(so.object > last || blended == 0);
        last = so.object;
        EXPECT_LT(so.joint, sk.joints.size());
        if (so.vertices.empty()) continue;
        ++blended;
        ASSERT_EQ(so.vertices.size(), b.ctx.object(so.object).positions.size());
        for (const GltfInfluence& g : so.vertices) {
            float sum = 0.0f;
            for (int i = 0; i < 4; ++i) {
                EXPECT_GE(g.weights[i], 0.0f);
                EXPECT_LT(g.joints[i], sk.joints.size());
                if (g.weights[i] == 0.0f) {
                    EXPECT_EQ(g.joints[i], 0);
                }
                sum += g.weights[i];
            }
            EXPECT_NEAR(sum, 1.0f, 1e-6f);
        }
    }
    EXPECT_GT(blended, 10u);  // the internodes
}

// Bending poses the skeleton: the unbent plant skinned with the joints where the bent plant
// has them lands on the bent plant. Nodes and internodes are exact up to the blend at the
// nodes; petioles curve toward the sky whichever way they point, so organs beyond them land
// near, not on, the bent plant's.
TEST(Skin, BendingPosesTheSkeleton) {
    Built b("tomato", 80.0f);
    const GltfSkeleton rest = exportSkeletons(b.arch).at(0);
    const std::vector<ObjectID> objects = b.arch.getAllPlantObjectIDs(b.plant);
    const Positions before = positionsOf(b.ctx, objects);
    std::vector<std::vector<vec3>> restNodes;
    for (const Shoot& s : b.arch.plant(b.plant).shoots)
        restNodes.push_back(s.removed ? std::vector<vec3>{}
                                      : bentNodePositions(b.arch, b.plant, s.id));
    bendPlant(b.arch, b.plant);
    const GltfSkeleton bent = exportSkeletons(b.arch).at(0);
    ASSERT_EQ(bent.joints.size(), rest.joints.size());
    double moved = 0.0;
    for (std::size_t j = 0; j < rest.joints.size(); ++j) {
        EXPECT_EQ(bent.joints[j].name, rest.joints[j].name);
        moved =
            std::max(moved, double(glm::length(bent.joints[j].position - rest.joints[j].position)));
    }
    EXPECT_GT(moved, 0.01);  // it bends
    // Posed on the unbent geometry (the bind pose was the unbent plant then), every organ
    // lands nearer the bent plant's than it was. Tube vertices are compared by where they lie
    // on their tube (distance from its axis, place along it): a tube's rings turn about its
    // axis as it bends (parallel transport), sliding vertices around, not off, its surface.
    const auto posed = skinned(before, rest, bent);
    std::map<std::string, double> posedError, restError;
    for (ObjectID o : objects) {
        const auto now = b.ctx.object(o).positions;
        const std::vector<glm::dvec3>& at = posed.at(o);
        const std::vector<vec3>& was = before.at(o);
        ASSERT_EQ(now.size(), at.size());
        const std::string organ = b.ctx.objectDataString(o, "organ").value_or("?");
        double& e = posedError[organ];
        double& r = restError[organ];
        for (std::size_t k = 0; k < at.size(); ++k) {
            r = std::max(r, glm::length(glm::dvec3(was[k]) - glm::dvec3(now[k])));
            if (organ != "internode") {
                e = std::max(e, glm::length(at[k] - glm::dvec3(now[k])));
                continue;
            }
            // On its tube: its axis from the joint of its internode to the next node.
            const int shoot = b.ctx.objectDataInt(o, "shootID").value();
            const int node = b.ctx.objectDataInt(o, "node").value();
            const std::vector<vec3> axis0 = restNodes.at(std::size_t(shoot));
            const std::vector<vec3> axis1 = bentNodePositions(b.arch, b.plant, unsigned(shoot));
            const auto place = [&](glm::dvec3 p, const std::vector<vec3>& a) {
                const glm::dvec3 from(a[std::size_t(node)]), to(a[std::size_t(node) + 1]);
                const glm::dvec3 u = glm::normalize(to - from);
                const double along = glm::dot(p - from, u);
                return glm::dvec2(along, glm::length(p - from - along * u));
            };
            e = std::max(e, glm::length(place(at[k], axis1) - place(glm::dvec3(was[k]), axis0)));
        }
    }
    // Internodes on their bent tubes; petioles and leaves, which curve toward the sky again
    // once bent, much nearer; fruit hang under gravity either way.
    EXPECT_GT(restError["internode"], 0.01);
    EXPECT_LT(posedError["internode"], 1e-4);
    EXPECT_LT(posedError["petiole"], 0.2 * restError["petiole"]);
    EXPECT_LT(posedError["leaf"], 0.5 * restError["leaf"]);
    EXPECT_LE(posedError["fruit"], restError["fruit"]);
}

namespace {

// `count` elements of an accessor's view, tightly packed, as plantarch writes them.
template <class T>
std::vector<T> values(const Glb& g, std::size_t accessor, std::size_t perElement) {
    const json& a = g.doc["accessors"][accessor];
    const json& v = g.doc["bufferViews"][a["bufferView"].get<std::size_t>()];
    std::vector<T> out(a["count"].get<std::size_t>() * perElement);
    std::memcpy(out.data(), g.bin.data() + v["byteOffset"].get<std::size_t>(),
                out.size() * sizeof(T));
    return out;
}

// Every node's world matrix, from the scene's roots down.
std::vector<glm::dmat4> worldMatrices(const json& doc) {
    std::vector<glm::dmat4> world(doc["nodes"].size(), glm::dmat4(1.0));
    std::vector<std::pair<std::size_t, glm::dmat4>> todo;
    for (const json& r : doc["scenes"][0]["nodes"]) todo.push_back({r.get<std::size_t>(), {}});
    for (auto& t : todo) t.second = glm::dmat4(1.0);
    while (!todo.empty()) {
        const auto [n, parent] = todo.back();
        todo.pop_back();
        const json& node = doc["nodes"][n];
        glm::dmat4 m(1.0);
        if (node.contains("translation")) {
            const json& t = node["translation"];
            m[3] = glm::dvec4(t[0].get<double>(), t[1].get<double>(), t[2].get<double>(), 1.0);
        }
        if (node.contains("rotation")) {
            const json& r = node["rotation"];
            const glm::dquat q(r[3].get<double>(), r[0].get<double>(), r[1].get<double>(),
                               r[2].get<double>());
            m = m * glm::dmat4(glm::mat3_cast(q));
        }
        EXPECT_FALSE(node.contains("scale") || node.contains("matrix"));
        world[n] = parent * m;
        for (const json& c : node.value("children", json::array()))
            todo.push_back({c.get<std::size_t>(), world[n]});
    }
    return world;
}

std::string skinnedGlb(int threads, const std::string& name) {
    const int before = omp_get_max_threads();
    omp_set_num_threads(threads);
    Built b("bean", 40.0f);
    GltfOptions o;
    o.plants = exportPlants(b.arch);
    o.skeletons = exportSkeletons(b.arch);
    const fs::path path = tempPath(name);
    writeGLTF(b.ctx, path.string(), o);
    omp_set_num_threads(before);
    const std::string bytes = readAll(path.string());
    fs::remove(path);
    return bytes;
}

}  // namespace

// The file's skin at bind pose (its joints' world matrices times their inverse bind matrices,
// blended by JOINTS_0 and WEIGHTS_0) puts every vertex where the plant node puts it unskinned:
// the plant as built, within 1e-5 relative.
TEST(Skin, GlbBindPoseReproducesThePlant) {
    Built b("bean", 40.0f);
    GltfOptions o;
    o.plants = exportPlants(b.arch);
    o.skeletons = exportSkeletons(b.arch);
    const fs::path path = tempPath("bean.glb");
    writeGLTF(b.ctx, path.string(), o);
    const Glb g = parseGlb(readAll(path.string()));
    fs::remove(path);
    ASSERT_EQ(g.doc["skins"].size(), 1u);
    const json& skin = g.doc["skins"][0];
    ASSERT_EQ(skin["joints"].size(), o.skeletons[0].joints.size());
    const std::vector<glm::dmat4> world = worldMatrices(g.doc);
    const std::vector<float> ibm = values<float>(g, skin["inverseBindMatrices"], 16);
    std::vector<glm::dmat4> joint;
    for (std::size_t j = 0; j < skin["joints"].size(); ++j) {
        glm::mat4 inverse;
        std::memcpy(&inverse[0][0], ibm.data() + 16 * j, 64);
        joint.push_back(world[skin["joints"][j].get<std::size_t>()] * glm::dmat4(inverse));
    }
    // The plant's node: the skeleton root's parent, placing the plant unskinned.
    std::size_t plantNode = 0;
    for (std::size_t n = 0; n < g.doc["nodes"].size(); ++n)
        for (const json& c : g.doc["nodes"][n].value("children", json::array()))
            if (c == skin["skeleton"]) plantNode = n;
    ASSERT_EQ(g.doc["nodes"][plantNode]["extras"]["plantID"], o.skeletons[0].plant);
    std::size_t vertices = 0, meshes = 0;
    double worst = 0.0;
    for (const json& r : g.doc["scenes"][0]["nodes"]) {
        const json& node = g.doc["nodes"][r.get<std::size_t>()];
        if (!node.contains("skin")) continue;
        ++meshes;
        EXPECT_FALSE(node.contains("translation") || node.contains("rotation"));
        for (const json& prim : g.doc["meshes"][node["mesh"].get<std::size_t>()]["primitives"]) {
            const json& at = prim["attributes"];
            const auto p = values<float>(g, at["POSITION"], 3);
            // Joints as unsigned bytes (up to 256 joints) or shorts, weights as normalized
            // unsigned bytes.
            std::vector<std::uint16_t> jt;
            const json& joints = g.doc["accessors"][at["JOINTS_0"].get<std::size_t>()];
            if (joints["componentType"] == 5121)
                for (std::uint8_t j : values<std::uint8_t>(g, at["JOINTS_0"], 4)) jt.push_back(j);
            else
                jt = values<std::uint16_t>(g, at["JOINTS_0"], 4);
            const json& weights = g.doc["accessors"][at["WEIGHTS_0"].get<std::size_t>()];
            EXPECT_EQ(weights["componentType"], 5121);
            EXPECT_TRUE(weights["normalized"].get<bool>());
            std::vector<float> w;
            for (std::uint8_t b : values<std::uint8_t>(g, at["WEIGHTS_0"], 4))
                w.push_back(float(b) / 255.0f);
            for (std::size_t k = 0; k < p.size() / 3; ++k) {
                const glm::dvec4 v(p[3 * k], p[3 * k + 1], p[3 * k + 2], 1.0);
                glm::dvec4 sum(0.0);
                double total = 0.0;
                for (int i = 0; i < 4; ++i) {
                    ASSERT_LT(jt[4 * k + i], joint.size());
                    if (w[4 * k + i] == 0.0f) {
                        EXPECT_EQ(jt[4 * k + i], 0);  // unused slots: joint 0
                    }
                    total += w[4 * k + i];
                    sum += double(w[4 * k + i]) * (joint[jt[4 * k + i]] * v);
                }
                EXPECT_NEAR(total, 1.0, 1e-6);
                const glm::dvec3 want(world[plantNode] * v);
                worst = std::max(
                    worst, glm::length(glm::dvec3(sum) - want) / std::max(1.0, glm::length(want)));
                ++vertices;
            }
        }
    }
    EXPECT_EQ(meshes, g.doc["meshes"].size());
    std::size_t all = 0;
    for (ObjectID id : b.arch.getAllPlantObjectIDs(b.plant))
        all += b.ctx.object(id).positions.size();
    EXPECT_EQ(vertices, all);
    EXPECT_LT(worst, 1e-5);
}

TEST(Skin, SameBytesOnAnyThreadCount) {
    const std::string one = skinnedGlb(1, "one.glb");
    EXPECT_NE(one.find("JOINTS_0"), std::string::npos);
    EXPECT_EQ(one, skinnedGlb(4, "four.glb"));
}

// A skeleton that does not fit the scene is one error naming the file, and writes nothing.
TEST(Skin, BadSkeletonsAreOneLineErrors) {
    Built b("bean", 20.0f);
    GltfOptions o;
    o.plants = exportPlants(b.arch);
    const std::vector<GltfSkeleton> good = exportSkeletons(b.arch);
    const fs::path path = tempPath("bad.glb");
    auto failure = [&](auto spoil) {
        o.skeletons = good;
        spoil(o.skeletons[0]);
        const Error e = errorOf([&] { writeGLTF(b.ctx, path.string(), o); });
        EXPECT_FALSE(fs::exists(path));
        EXPECT_EQ(e.file(), path.string());
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
        return e;
    };
    failure([](GltfSkeleton& s) { s.joints[2].parent = 5; });
    failure([](GltfSkeleton& s) { s.joints[1].position.x = std::nanf(""); });
    failure([](GltfSkeleton& s) { s.joints[1].rotation = {0, 0, 0, 0}; });
    failure([](GltfSkeleton& s) { s.joints.clear(); });
    failure([](GltfSkeleton& s) { s.objects.front().joint = 60000; });
    failure([](GltfSkeleton& s) {
        for (GltfSkinnedObject& so : s.objects)
            if (!so.vertices.empty()) so.vertices.pop_back();
    });
    failure([](GltfSkeleton& s) {
        for (GltfSkinnedObject& so : s.objects)
            if (!so.vertices.empty()) so.vertices[0].weights = {0.5f, 0.2f, 0.0f, 0.0f};
    });
    failure([](GltfSkeleton& s) {
        for (GltfSkinnedObject& so : s.objects)
            if (!so.vertices.empty()) so.vertices[0].weights = {2.0f, -1.0f, 0.0f, 0.0f};
    });
}

// USD: the plant a SkelRoot holding its Skeleton (a joint path, bind and rest transform per
// joint, the rest transforms composing to the bind transforms), its meshes bound to it with
// four joint indices and weights per point, the weights summing to 1.
TEST(Skin, UsdSkelroot) {
    Built b("bean", 30.0f);
    UsdOptions o;
    o.plants = exportPlants(b.arch);
    o.skeletons = exportSkeletons(b.arch);
    const std::size_t joints = o.skeletons[0].joints.size();
    const fs::path path = tempPath("bean.usda");
    writeUSDA(b.ctx, path.string(), o);
    const std::string text = readAll(path.string());
    fs::remove(path);
    EXPECT_NE(text.find("def SkelRoot \"bean_"), std::string::npos);
    // The array after `key = [` up to its `]`, split at ", " outside parentheses.
    auto array = [&](std::size_t from, const std::string& key) {
        const std::size_t at = text.find(key + " = [", from);
        EXPECT_NE(at, std::string::npos) << key;
        std::vector<std::string> items;
        int depth = 0;
        std::string item;
        for (std::size_t i = at + key.size() + 4; i < text.size(); ++i) {
            const char c = text[i];
            if (depth == 0 && c == ']') break;
            if (c == '(') ++depth;
            if (c == ')') --depth;
            if (depth == 0 && c == ',') {
                items.push_back(item);
                item.clear();
                ++i;  // the space
                continue;
            }
            item += c;
        }
        if (!item.empty()) items.push_back(item);
        return items;
    };
    const std::size_t skeleton = text.find("def Skeleton \"skeleton\"");
    ASSERT_NE(skeleton, std::string::npos);
    const auto paths = array(skeleton, "uniform token[] joints");
    ASSERT_EQ(paths.size(), joints);
    EXPECT_EQ(paths[0], "\"root\"");
    const auto bind = array(skeleton, "uniform matrix4d[] bindTransforms");
    const auto rest = array(skeleton, "uniform matrix4d[] restTransforms");
    ASSERT_EQ(bind.size(), joints);
    ASSERT_EQ(rest.size(), joints);
    auto matrix = [](std::string m) {
        for (char& c : m)
            if (c == '(' || c == ')' || c == ',') c = ' ';
        std::istringstream in(m);
        glm::dmat4 out;
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) in >> out[r][c];  // USD rows: glm columns
        return out;
    };
    for (std::size_t j = 1; j < joints; ++j) {
        const GltfJoint& jt = o.skeletons[0].joints[j];
        // A joint's path is its parent's and its own name.
        EXPECT_EQ(paths[j].rfind(paths[std::size_t(jt.parent)].substr(
                                     0, paths[std::size_t(jt.parent)].size() - 1) +
                                     "/",
                                 0),
                  0u);
        const glm::dmat4 composed = matrix(bind[std::size_t(jt.parent)]) * matrix(rest[j]);
        const glm::dmat4 want = matrix(bind[j]);
        for (int c = 0; c < 4; ++c) EXPECT_LT(glm::length(composed[c] - want[c]), 1e-5) << paths[j];
    }
    std::size_t meshes = 0;
    for (std::size_t at = text.find("def Mesh"); at != std::string::npos;
         at = text.find("def Mesh", at + 1)) {
        ++meshes;
        const std::size_t points = array(at, "point3f[] points").size();
        const auto indices = array(at, "int[] primvars:skel:jointIndices");
        const auto weights = array(at, "float[] primvars:skel:jointWeights");
        ASSERT_EQ(indices.size(), 4 * points);
        ASSERT_EQ(weights.size(), 4 * points);
        for (std::size_t k = 0; k < points; ++k) {
            double sum = 0.0;
            for (int i = 0; i < 4; ++i) {
                EXPECT_LT(std::stoul(indices[4 * k + std::size_t(i)]), joints);
                const double w = std::stod(weights[4 * k + std::size_t(i)]);
                EXPECT_GE(w, 0.0);
                sum += w;
            }
            EXPECT_NEAR(sum, 1.0, 1e-6);
        }
        EXPECT_NE(text.find("rel skel:skeleton = </plantarch/bean_", at), std::string::npos);
    }
    EXPECT_GE(meshes, 3u);
    // A skeleton that does not fit: one error naming the file, nothing written.
    o.skeletons[0].joints[3].parent = 7;
    try {
        writeUSDA(b.ctx, path.string(), o);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), path.string());
    }
    EXPECT_FALSE(fs::exists(path));
}

// The command line: --skin skins .glb, .gltf and .usda outputs and leaves others as they were;
// combinations it cannot write are one line and exit 2, leaving no file.
TEST(Skin, CommandLine) {
    const fs::path dir = tempPath("cli");
    fs::create_directories(dir);
    const std::string d = dir.string() + "/";
    fs::create_directories(d + "plain");
    cli::Result r = cli::run("--seed 3 build bean --age 20 --skin -o " + d + "s.glb -o " + d +
                             "s.usda -o " + d + "s.obj -o " + d + "s.ply");
    ASSERT_EQ(r.status, 0) << r.out;
    r = cli::run("--seed 3 build bean --age 20 -o " + d + "plain/s.obj -o " + d + "plain/s.ply");
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_TRUE(readAll(d + "s.obj") == readAll(d + "plain/s.obj"));
    EXPECT_TRUE(readAll(d + "s.ply") == readAll(d + "plain/s.ply"));
    EXPECT_EQ(parseGlb(readAll(d + "s.glb")).doc["skins"].size(), 1u);
    EXPECT_NE(readAll(d + "s.usda").find("def SkelRoot"), std::string::npos);
    for (const char* bad : {"--nodes organ", "--lod reduced"}) {
        r = cli::run(std::string("--seed 3 build bean --age 20 --skin ") + bad + " -o " + d +
                     "bad.glb");
        EXPECT_EQ(r.status, 2) << bad << ": " << r.out;
        EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
        EXPECT_FALSE(fs::exists(d + "bad.glb"));
    }
    fs::remove_all(dir);
}

// GltfOptions::windDegrees: a looping animation "wind" turning every joint but the root, unit
// rotations over one period whose first and last keys agree; none without it; out of range an
// error.
TEST(Skin, WindAnimation) {
    Built b("bean", 30.0f);
    GltfOptions o;
    o.plants = exportPlants(b.arch);
    o.skeletons = exportSkeletons(b.arch);
    const fs::path path = tempPath("wind.glb");
    writeGLTF(b.ctx, path.string(), o);
    EXPECT_FALSE(parseGlb(readAll(path.string())).doc.contains("animations"));
    o.windDegrees = 15.0f;
    writeGLTF(b.ctx, path.string(), o);
    const Glb g = parseGlb(readAll(path.string()));
    ASSERT_EQ(g.doc["animations"].size(), 1u);
    const json& wind = g.doc["animations"][0];
    EXPECT_EQ(wind["name"], "wind");
    const std::size_t joints = o.skeletons[0].joints.size();
    ASSERT_EQ(wind["channels"].size(), joints - 1);
    std::set<std::size_t> targets;
    for (const json& c : wind["channels"]) {
        EXPECT_EQ(c["target"]["path"], "rotation");
        targets.insert(c["target"]["node"].get<std::size_t>());
        const json& sampler = wind["samplers"][c["sampler"].get<std::size_t>()];
        const std::vector<float> times = values<float>(g, sampler["input"], 1);
        EXPECT_EQ(times.front(), 0.0f);
        EXPECT_FLOAT_EQ(times.back(), 2.0f);
        const std::vector<float> q = values<float>(g, sampler["output"], 4);
        ASSERT_EQ(q.size(), 4 * times.size());
        for (std::size_t k = 0; k < times.size(); ++k)
            EXPECT_NEAR(std::hypot(std::hypot(q[4 * k], q[4 * k + 1]),
                                   std::hypot(q[4 * k + 2], q[4 * k + 3])),
                        1.0, 1e-5);
        for (int i = 0; i < 4; ++i)
            EXPECT_NEAR(q[std::size_t(i)], q[q.size() - 4 + std::size_t(i)], 1e-5);
    }
    const json& skin = g.doc["skins"][0]["joints"];
    for (std::size_t j = 1; j < joints; ++j) EXPECT_TRUE(targets.count(skin[j].get<std::size_t>()));
    o.windDegrees = 120.0f;
    EXPECT_THROW(writeGLTF(b.ctx, path.string(), o), Error);
    fs::remove(path);
}
