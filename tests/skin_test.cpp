// A wind-ready skeleton (plantarch/ExportPlants.h exportSkeletons, GltfOptions::skeletons):
// one joint per internode, weights that sum to 1, the bind pose that reproduces the plant,
// bending that poses it, skinned glTF and USD files, determinism and hostile inputs.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/quaternion.hpp>
#include <map>
#include <string>
#include <vector>

#include "plantarch/Bending.h"
#include "plantarch/ExportPlants.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;

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
