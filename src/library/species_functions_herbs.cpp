// Named per-phytomer functions of the library species: vegetable and cereal crops (tomato,
// cherry tomato, capsicum, maize, sorghum, wheat, asparagus, butter lettuce).

#include <algorithm>
#include <cmath>

#include "library/species_functions.h"
#include "model/architecture_impl.h"
#include "plantarch/Error.h"

namespace plantarch::species_functions {

namespace {

void scaleLeaves(Phytomer& ph, float factor) {
    for (Petiole& p : ph.petioles)
        for (LeafOrgan& l : p.leaves) l.scale *= factor;
}

// Removes a phytomer's leaves together with their petioles (a petiole of zero size is not
// drawn); the node keeps its buds.
void removeLeaves(Phytomer& ph) {
    for (Petiole& p : ph.petioles) {
        for (LeafOrgan& l : p.leaves) l.removed = true;
        p.length = 0.0f;
        p.radius = 0.0f;
    }
}

// Tomato: no flowers on the main stem's first 8 nodes; shoots of rank 2 and up neither branch
// nor flower. Leaves made early start smaller (50 % at emergence, full size from day 10), and
// so do internodes (70 %, full length from day 10).
void tomatoPhytomer(PhytomerCreationContext& c) {
    if (c.shoot.rank == 0 && c.nodeIndex < 8) killFloralBuds(c.phytomer);
    if (c.shoot.rank > 1) {
        killFloralBuds(c.phytomer);
        killVegetativeBuds(c.phytomer);
    }
    const float age = float(c.plantAge);
    scaleLeaves(c.phytomer, std::min(1.0f, 0.5f + 0.5f * age / 10.0f));
    c.phytomer.internode.length *= std::min(1.0f, 0.7f + 0.3f * age / 10.0f);
}

// Cherry tomato (trained on a string, indeterminate): the first 8 nodes of every shoot, and
// all of shoots of rank 2 and up, neither branch nor flower. Leaves made early start smaller
// (70 %, full size from day 15), and so do internodes (70 %, full length from day 10).
void cherryTomatoPhytomer(PhytomerCreationContext& c) {
    if (c.nodeIndex < 8 || c.shoot.rank > 1) {
        killFloralBuds(c.phytomer);
        killVegetativeBuds(c.phytomer);
    }
    const float age = float(c.plantAge);
    scaleLeaves(c.phytomer, std::min(1.0f, 0.7f + 0.3f * age / 15.0f));
    c.phytomer.internode.length *= std::min(1.0f, 0.7f + 0.3f * age / 10.0f);
}

// Cherry tomato pruning: from day 101 on, the leaves (with their petioles) of every node
// whose internode starts below 1 m are stripped, as growers clear the lower canopy.
constexpr double kCherryTomatoPruningAge = 101.0;
constexpr float kCherryTomatoPruningHeight = 1.0f;

void cherryTomatoPruning(PhytomerCallbackContext& c) {
    if (c.plantAge < kCherryTomatoPruningAge) return;
    if (c.nodeBase.z - c.plant.base.z < kCherryTomatoPruningHeight) removeLeaves(c.phytomer);
}

// Capsicum: the main stem's first 6 nodes are bare (no leaf, petiole, branch or flower);
// shoots of rank 2 and up neither branch nor flower. Leaves grow with the node, from 60 % of
// full size at node 0 to full size at node 5; main-stem internodes made at emergence are 5 %
// of full length, full length from day 15.
void capsicumPhytomer(PhytomerCreationContext& c) {
    if (c.shoot.rank == 0 && c.nodeIndex < 6) {
        killFloralBuds(c.phytomer);
        killVegetativeBuds(c.phytomer);
        removeLeaves(c.phytomer);
    }
    if (c.shoot.rank >= 2) {
        killFloralBuds(c.phytomer);
        killVegetativeBuds(c.phytomer);
    }
    scaleLeaves(c.phytomer, std::min(1.0f, 0.6f + 0.4f * float(c.nodeIndex) / 5.0f));
    if (c.shoot.rank == 0)
        c.phytomer.internode.length *= std::min(1.0f, 0.05f + 0.95f * float(c.plantAge) / 15.0f);
}

// Maize: leaves grow from 70 % of full size at node 0 to full size at node 5 (and so do those
// internodes), and shrink again over the top nodes (to about 77 % at the flag leaf). Nodes 9
// to 11 bear an ear: their floral bud is forced to flower and drawn from the shoot type
// "ear" (a short thick shank, the ear fruit); every other node's floral bud is removed, so the
// only other inflorescence is the tassel, the shoot's terminal floral bud.
constexpr const char* kMaizeEarType = "ear";

void maizePhytomer(PhytomerCreationContext& c) {
    const int node = int(c.nodeIndex), n = c.shootMaxNodes;
    float s = 1.0f;
    if (node <= 5) {
        s = std::min(1.0f, 0.7f + 0.3f * float(node) / 5.0f);
        c.phytomer.internode.length *= s;
    } else if (node >= n - 5) {
        s = std::min(1.0f, 0.65f + 0.35f * float(n - node) / 3.0f);
    }
    scaleLeaves(c.phytomer, s);
    if (node < 9 || node > 11) {
        killFloralBuds(c.phytomer);
        return;
    }
    if (!c.plant.shootTypes.count(kMaizeEarType))
        throw Error("maize_phytomer needs a shoot type for the ears",
                    {.parameter = "shoot_type_label",
                     .value = kMaizeEarType,
                     .validRange = "a shoot type labelled 'ear' in the species"});
    for (Petiole& p : c.phytomer.petioles)
        for (FloralBud& b : p.floralBuds)
            if (b.stage == FloralStage::Bud && b.state == BudState::Dormant) {
                b.state = BudState::Active;
                b.parametersLabel = kMaizeEarType;
            }
}

// Small grains (sorghum, wheat): leaves and internodes grow from 70 % of full size at node 0
// to full size at node 5.
void scaleEarlyGrassNodes(PhytomerCreationContext& c) {
    const float s = std::min(1.0f, 0.7f + 0.3f * float(c.nodeIndex) / 5.0f);
    scaleLeaves(c.phytomer, s);
    c.phytomer.internode.length *= s;
}

// Sorghum: as wheat, and the flag leaf (the shoot's last node) stands 25 degrees more upright
// (its petiole pitch, negative for the other blades, is raised by 25 degrees).
void sorghumPhytomer(PhytomerCreationContext& c) {
    scaleEarlyGrassNodes(c);
    if (int(c.nodeIndex) + 1 == c.shootMaxNodes)
        for (Petiole& p : c.phytomer.petioles) p.pitch += 25.0f;
}

// Asparagus: the first 3 nodes of every shoot make no branch and carry cladodes at 60 % of
// full size.
void asparagusPhytomer(PhytomerCreationContext& c) {
    if (c.nodeIndex > 2) return;
    scaleLeaves(c.phytomer, 0.6f);
    killVegetativeBuds(c.phytomer);
}

// Asparagus cladode: a slender three-sided spine tapering from its base to a point, in
// prototype units (length 1 along +x from the origin). Its base diameter is the prototype's
// leaf_aspect_ratio and `subdivisions` sets the segments along it: 9 to 15 triangles where a
// flat needle outline meshed to its true shape takes about 150.
OrganPrototype asparagusCladode(const LeafPrototype& p, Rng& rng, int leaflet) {
    (void)leaflet;
    constexpr int kSides = 3;
    constexpr float kPi = 3.14159265358979f;
    const float radius = 0.5f * p.leaf_aspect_ratio.sample(rng);
    const int segments = int(std::clamp(p.subdivisions, 1u, 8u));
    Mesh m;
    for (int k = 0; k < segments; ++k) {  // rings at x = k / segments, tapering linearly
        const float x = float(k) / float(segments), r = radius * (1.0f - x);
        for (int j = 0; j < kSides; ++j) {
            const float a = 2.0f * kPi * float(j) / float(kSides);
            m.positions.push_back({x, r * std::cos(a), r * std::sin(a)});
        }
    }
    const auto tip = std::uint32_t(m.positions.size());
    m.positions.push_back({1.0f, 0.0f, 0.0f});
    auto ring = [](int k, int j) { return std::uint32_t(k * kSides + (j % kSides)); };
    for (int k = 0; k < segments; ++k)
        for (int j = 0; j < kSides; ++j) {
            if (k + 1 < segments) {
                m.indices.insert(m.indices.end(), {ring(k, j), ring(k, j + 1), ring(k + 1, j + 1)});
                m.indices.insert(m.indices.end(), {ring(k, j), ring(k + 1, j + 1), ring(k + 1, j)});
            } else {
                m.indices.insert(m.indices.end(), {ring(k, j), ring(k, j + 1), tip});
            }
        }
    m.indices.insert(m.indices.end(), {ring(0, 0), ring(0, 2), ring(0, 1)});  // the base
    return OrganPrototype{{std::move(m), Material{p.color, "", "leaf"}}};
}

// Butter lettuce: each leaf is pitched down by 60 degrees x (max_nodes - node) / max_nodes,
// so the outer (older) leaves spread and droop and the inner ones stand upright in a head.
void butterLettucePhytomer(PhytomerCreationContext& c) {
    if (c.shootMaxNodes <= 0) return;
    const float fact = float(c.shootMaxNodes - int(c.nodeIndex)) / float(c.shootMaxNodes);
    for (Petiole& p : c.phytomer.petioles)
        for (LeafOrgan& l : p.leaves) l.pitch -= 60.0f * fact;
}

}  // namespace

void registerHerbs(PlantArchitecture& arch) {
    arch.registerPhytomerCreationFunction("tomato_phytomer", tomatoPhytomer);
    arch.registerPhytomerCreationFunction("cherrytomato_phytomer", cherryTomatoPhytomer);
    arch.registerPhytomerCallbackFunction("cherrytomato_pruning", cherryTomatoPruning);
    arch.registerPhytomerCreationFunction("capsicum_phytomer", capsicumPhytomer);
    arch.registerPhytomerCreationFunction("maize_phytomer", maizePhytomer);
    arch.registerPhytomerCreationFunction("sorghum_phytomer", sorghumPhytomer);
    arch.registerPhytomerCreationFunction("wheat_phytomer", scaleEarlyGrassNodes);
    arch.registerPhytomerCreationFunction("asparagus_phytomer", asparagusPhytomer);
    arch.registerLeafPrototype("asparagus_cladode", asparagusCladode);
    arch.registerPhytomerCreationFunction("butterlettuce_phytomer", butterLettucePhytomer);
}

}  // namespace plantarch::species_functions
