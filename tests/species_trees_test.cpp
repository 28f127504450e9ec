// The nut trees of the species library (almond and its two training variants, pistachio,
// walnut): each rule function's effect on grown plants, the build parameters of the trained
// young trees, and the phenology of the renders' age.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "core/math.h"
#include "error_of.h"
#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"
#include "plantarch/SpeciesIO.h"

using namespace plantarch;
using plantarch::testing::errorOf;

namespace {

// One library plant in its own scene.
struct Tree {
    std::unique_ptr<Context> ctx = std::make_unique<Context>();
    std::unique_ptr<PlantArchitecture> arch = std::make_unique<PlantArchitecture>(ctx.get());
    unsigned id = 0;
    const PlantInstance& plant() const { return arch->plant(id); }
};

Tree grow(const std::string& species, float age, const std::map<std::string, float>& params = {},
          std::uint64_t seed = 42) {
    Tree t;
    t.arch->setSeed(seed);
    t.arch->loadPlantModelFromLibrary(species);
    t.id = t.arch->buildPlantInstanceFromLibrary(vec3(0.0f), age, params);
    return t;
}

std::vector<const Shoot*> shootsOfType(const PlantInstance& p, const std::string& type) {
    std::vector<const Shoot*> out;
    for (const Shoot& s : p.shoots)
        if (!s.removed && s.type == type) out.push_back(&s);
    return out;
}

bool flowered(const FloralBud& b) {
    return b.state == BudState::Broken;
}

// Phytomers of a shoot made in the season that began at `begin` (plant age) and ended before
// `end`.
int nodesBornIn(const Shoot& s, double begin, double end) {
    int n = 0;
    for (const Phytomer& ph : s.phytomers) n += ph.birth >= begin && ph.birth < end;
    return n;
}

// Objects of the plant's flowers, closed and open.
std::size_t flowerObjectCount(const PlantArchitecture& arch, unsigned plantID) {
    return arch.getPlantObjectIDs(plantID, OrganKind::FlowerClosed).size() +
           arch.getPlantObjectIDs(plantID, OrganKind::FlowerOpen).size();
}

}  // namespace

// ---- almond ----------------------------------------------------------------------------

TEST(SpeciesTreesAlmond, ASpurGrowsSevenNodesASeasonALongShootTwenty) {
    // Two shoots added by hand to a scaffold of the planted (dormant) tree: one with 5 mm
    // internodes (a spur), one with 2 cm internodes.
    Tree t = grow("almond", 0.0f);
    const unsigned scaffold = shootsOfType(t.plant(), "scaffold").at(0)->id;
    ShootSpec spec;
    spec.shootType = "proleptic";
    spec.size.internodeRadius = 0.002f;
    spec.size.internodeLengthMax = 0.005f;
    const unsigned spur = t.arch->addChildShoot(t.id, scaffold, 1, spec);
    spec.size.internodeLengthMax = 0.02f;
    const unsigned shoot = t.arch->addChildShoot(t.id, scaffold, 3, spec);
    EXPECT_EQ(t.plant().shoots[spur].maxNodesPerSeason, 7);
    EXPECT_EQ(t.plant().shoots[shoot].maxNodesPerSeason, 20);  // the type's value

    // Dormancy breaks at day 90 and again at 455; each season adds 7 nodes to the spur
    // (1 + 7 + 7) and 20 to the long shoot (1 + 20 + 20).
    t.arch->advanceTime(300.0);
    EXPECT_EQ(t.plant().shoots[spur].phytomers.size(), 8u);
    EXPECT_EQ(t.plant().shoots[shoot].phytomers.size(), 21u);
    t.arch->advanceTime(330.0);
    const Shoot& s = t.plant().shoots[spur];
    EXPECT_EQ(s.phytomers.size(), 15u);
    EXPECT_EQ(t.plant().shoots[shoot].phytomers.size(), 41u);
    // Spur nodes: no branch, no axillary flower, leaves at 80 % of the type's 0.12 m.
    EXPECT_TRUE(s.children.empty());
    for (const Phytomer& ph : s.phytomers)
        for (const Petiole& pt : ph.petioles) {
            for (const VegetativeBud& b : pt.vegetativeBuds) EXPECT_EQ(b.state, BudState::Dead);
            for (const FloralBud& b : pt.floralBuds) EXPECT_FALSE(flowered(b));
            for (const LeafOrgan& l : pt.leaves) EXPECT_NEAR(l.scale, 0.096f, 1e-6f);
        }
    const Shoot& longShoot = t.plant().shoots[shoot];
    EXPECT_NEAR(longShoot.phytomers.back().petioles[0].leaves[0].scale, 0.12f, 1e-6f);
}

TEST(SpeciesTreesAlmond, GrownTreeHasSpursThatObeyTheRule) {
    // Buds far below a shoot tip grow into spurs (the scaffold type's acrotonic internode
    // decay of 2 mm per node); every spur keeps the rule over three seasons.
    Tree t = grow("almond", 1000.0f);
    const PlantInstance& p = t.plant();
    int spurs = 0, longShoots = 0;
    const double breaks[] = {90.0, 455.0, 820.0, 1185.0};
    for (const Shoot* s : shootsOfType(p, "proleptic")) {
        const bool spur = s->phytomers[0].internode.length < 0.01f;
        if (!spur) {
            ++longShoots;
            EXPECT_EQ(s->maxNodesPerSeason, 20);
            continue;
        }
        ++spurs;
        EXPECT_EQ(s->maxNodesPerSeason, 7);
        EXPECT_TRUE(s->children.empty());
        // At most 7 nodes added a season; the node the spur started with is not one of them.
        const double start = s->phytomers[0].birth;
        for (int k = 0; k < 3; ++k)
            EXPECT_LE(nodesBornIn(*s, breaks[k], breaks[k + 1]),
                      7 + int(start >= breaks[k] && start < breaks[k + 1]));
    }
    EXPECT_GT(spurs, 0);
    EXPECT_GT(longShoots, 0);
}

TEST(SpeciesTreesAlmond, RepresentativeAgeIsMidSecondSeasonWithFruit) {
    // 630 days: planted dormant, bud break at 90, leaf fall at 365, bud break at 455: in
    // leaf, flowers over (open 3 days after bud break, fruit set 7 days later), fruit grown.
    Tree t = grow("almond", 630.0f);
    EXPECT_EQ(t.arch->getPhenologyStage(t.id), PhenologyStage::Reproductive);
    EXPECT_EQ(t.plant().season, 2);
    EXPECT_EQ(flowerObjectCount(*t.arch, t.id), 0u);
    EXPECT_FALSE(t.arch->getPlantObjectIDs(t.id, OrganKind::Fruit).empty());
    const unsigned leaves = t.arch->getPlantLeafCount(t.id);
    // The reference's mean at this age is 462 leaves (28 shoots): within 25 % of it.
    EXPECT_GE(leaves, unsigned(0.75 * 462));
    EXPECT_LE(leaves, unsigned(1.25 * 462));
    // In winter (day 400) the tree is bare and dormant.
    Tree winter = grow("almond", 400.0f);
    EXPECT_EQ(winter.arch->getPhenologyStage(winter.id), PhenologyStage::Dormant);
    EXPECT_EQ(winter.arch->getPlantLeafCount(winter.id), 0u);
}

TEST(SpeciesTreesAlmond, TrunkIsBareHeadedAndCarriesTheScaffolds) {
    Tree t = grow("almond", 630.0f);
    const PlantInstance& p = t.plant();
    const Shoot& trunk = p.shoots[0];
    EXPECT_EQ(trunk.type, "trunk");
    EXPECT_EQ(trunk.phytomers.size(), 20u);  // 0.6 m of 3 cm internodes
    for (const Phytomer& ph : trunk.phytomers)
        for (const Petiole& pt : ph.petioles)
            for (const LeafOrgan& l : pt.leaves) EXPECT_TRUE(l.removed);
    // Only the scaffolds and the 1 cm top node grow from the trunk.
    for (unsigned c : trunk.children) {
        const Shoot& child = p.shoots[c];
        EXPECT_TRUE(child.type == "scaffold" || child.type == "trunk") << child.type;
    }
    EXPECT_EQ(shootsOfType(p, "scaffold").size(), 4u);
    EXPECT_GT(trunk.phytomers[0].internode.radius, 0.015f);  // thickened by the canopy
}

TEST(SpeciesTreesAlmond, BuildParametersMoveTheScaffolds) {
    for (float h : {0.45f, 0.6f, 1.2f}) {
        SCOPED_TRACE(h);
        Tree t = grow("almond", 0.0f, {{"trunk_height", h}});
        const PlantInstance& p = t.plant();
        const unsigned nodes = unsigned(std::floor(h / 0.03f + 1e-4f));
        EXPECT_EQ(p.shoots[0].phytomers.size(), nodes);
        // The trunk leans at most 9 degrees; its 1 cm top node stands above it.
        const float stem = t.arch->getPlantStemHeight(t.id);
        EXPECT_GT(stem, 0.98f * h);
        EXPECT_LT(stem, h + 0.011f);
        // Scaffold 0 on the top node, the others on the trunk's highest nodes.
        std::vector<int> onTrunk;
        for (const Shoot* s : shootsOfType(p, "scaffold"))
            if (s->parent == 0) onTrunk.push_back(s->parentNode);
        EXPECT_EQ(onTrunk, (std::vector<int>{int(nodes) - 1, int(nodes) - 2, int(nodes) - 3}));
    }
    for (int n : {2, 6}) {
        Tree t = grow("almond", 0.0f, {{"num_scaffolds", float(n)}});
        EXPECT_EQ(shootsOfType(t.plant(), "scaffold").size(), std::size_t(n));
    }
    for (float angle : {20.0f, 70.0f}) {
        Tree t = grow("almond", 0.0f, {{"scaffold_angle", angle}});
        for (const Shoot* s : shootsOfType(t.plant(), "scaffold")) {
            // Insertion angle = the step's pitch: scaffold_angle +- 0.1 rad.
            EXPECT_NEAR(s->insertionAngle, angle, 5.74f);
            const vec3 axis = s->phytomers[0].internode.guide;
            EXPECT_NEAR(std::acos(axis.z) / kDeg, angle, 5.74f + 9.0f);  // + trunk lean
        }
    }
}

TEST(SpeciesTreesAlmond, BuildParameterErrors) {
    const Error high = errorOf([] { grow("almond", 0.0f, {{"trunk_height", 3.5f}}); });
    EXPECT_EQ(high.parameter(), "trunk_height");
    EXPECT_EQ(high.validRange(), "0.1 to 3 m");
    const Error many = errorOf([] { grow("almond", 0.0f, {{"num_scaffolds", 9}}); });
    EXPECT_EQ(many.parameter(), "num_scaffolds");
    const Error angle = errorOf([] { grow("almond", 0.0f, {{"scaffold_angle", 10}}); });
    EXPECT_EQ(angle.parameter(), "scaffold_angle");
    // A 9 cm trunk has 3 nodes: it cannot hold 8 scaffolds one node apart.
    const Error crowded = errorOf([] {
        grow("almond", 0.0f, {{"trunk_height", 0.1f}, {"num_scaffolds", 8}});
    });
    EXPECT_NE(crowded.parameter().find(".node"), std::string::npos) << crowded.what();
    EXPECT_NE(crowded.file().find("almond.xml"), std::string::npos);
}

// ---- almond training variants ------------------------------------------------------------

TEST(SpeciesTreesAlmondVariants, FixedLayoutsOfTheReferenceAreTheDefaults) {
    struct Layout {
        const char* species;
        unsigned trunkNodes, scaffolds;
        float pitchMin, pitchMax;
    };
    for (const Layout& l :
         {Layout{"almond_aldrich", 19, 4, 5, 35}, Layout{"almond_wood_colony", 14, 5, 45, 60}}) {
        SCOPED_TRACE(l.species);
        std::set<std::size_t> nodeCounts;
        for (std::uint64_t seed = 1; seed <= 6; ++seed) {
            Tree t = grow(l.species, 0.0f, {}, seed);
            const PlantInstance& p = t.plant();
            EXPECT_EQ(p.shoots[0].phytomers.size(), l.trunkNodes);
            const auto scaffolds = shootsOfType(p, "scaffold");
            ASSERT_EQ(scaffolds.size(), l.scaffolds);
            for (const Shoot* s : scaffolds) {
                nodeCounts.insert(s->phytomers.size());
                EXPECT_GE(s->insertionAngle, l.pitchMin);
                EXPECT_LE(s->insertionAngle, l.pitchMax);
            }
        }
        // 7, 8 or 9 nodes per scaffold, each of them occurring.
        EXPECT_EQ(nodeCounts, (std::set<std::size_t>{7, 8, 9}));
    }
}

TEST(SpeciesTreesAlmondVariants, TrunkHeightAndScaffoldCountAdjustTheLayout) {
    Tree t = grow("almond_wood_colony", 0.0f, {{"trunk_height", 0.9f}, {"num_scaffolds", 3}});
    EXPECT_EQ(t.plant().shoots[0].phytomers.size(), 30u);
    EXPECT_EQ(shootsOfType(t.plant(), "scaffold").size(), 3u);
    // The scaffold angles are the variant's own spread, not a parameter.
    const Error e = errorOf([] { grow("almond_aldrich", 0.0f, {{"scaffold_angle", 40}}); });
    EXPECT_EQ(e.parameter(), "scaffold_angle");
    EXPECT_EQ(e.validRange(), "one of: trunk_height, num_scaffolds");
}

TEST(SpeciesTreesAlmondVariants, ShapesAtTheRepresentativeAge) {
    // ref renders at 630 d: Aldrich an upright vase 2.12 m tall, Wood Colony a low, wide one
    // of 1.38 m. Wood Colony spreads wider than it is tall above its trunk.
    Tree aldrich = grow("almond_aldrich", 630.0f);
    Tree wood = grow("almond_wood_colony", 630.0f);
    const float hA = aldrich.arch->getPlantHeight(aldrich.id);
    const float hW = wood.arch->getPlantHeight(wood.id);
    EXPECT_GT(hA, 1.5f);
    EXPECT_LT(hA, 3.0f);
    EXPECT_GT(hW, 0.9f);
    EXPECT_LT(hW, 2.0f);
    auto spread = [](const Tree& t) {
        float r = 0.0f;
        t.ctx->forEachObject([&](const ObjectView& v) {
            for (const vec3& q : v.positions) r = std::max(r, std::hypot(q.x, q.y));
        });
        return r;
    };
    EXPECT_GT(spread(wood) / (hW - 0.42f), spread(aldrich) / (hA - 0.57f));
    for (const Tree* t : {&aldrich, &wood}) {
        EXPECT_EQ(t->arch->getPhenologyStage(t->id), PhenologyStage::Reproductive);
        EXPECT_GT(t->arch->getPlantLeafCount(t->id), 150u);
    }
}

// ---- walnut ------------------------------------------------------------------------------

TEST(SpeciesTreesWalnut, FirstFourNodesOfEveryShootAreBlind) {
    // No branch and no flower from nodes 0 to 3 of any scaffold or branch, over three
    // seasons; further out the shoots branch and flower.
    for (float age : {630.0f, 1000.0f}) {
        SCOPED_TRACE(age);
        Tree t = grow("walnut", age);
        const PlantInstance& p = t.plant();
        int branchesOut = 0, flowersOut = 0, readyBudsOut = 0;
        for (const Shoot& s : p.shoots) {
            if (s.removed || s.type == "trunk") continue;
            for (unsigned k = 0; k < s.phytomers.size(); ++k)
                for (const Petiole& pt : s.phytomers[k].petioles) {
                    for (const VegetativeBud& b : pt.vegetativeBuds) {
                        if (k < 4)
                            EXPECT_EQ(b.state, BudState::Dead) << s.id << " node " << k;
                        else
                            branchesOut += b.state == BudState::Broken;
                        if (k >= 4) readyBudsOut += b.state == BudState::Dormant;
                    }
                    for (const FloralBud& b : pt.floralBuds) {
                        if (k < 4)
                            EXPECT_FALSE(flowered(b)) << s.id << " node " << k;
                        else
                            flowersOut += flowered(b);
                    }
                }
            for (unsigned c : s.children) EXPECT_GE(p.shoots[c].parentNode, 4);
        }
        EXPECT_GT(branchesOut, 0);
        EXPECT_GT(flowersOut, 0);
        EXPECT_GT(readyBudsOut, 0);  // buds of this season's nodes wait for next spring
    }
}

TEST(SpeciesTreesWalnut, PhenologyAtTheRepresentativeAge) {
    // Bud break at 165 and 530 days, leaf fall at 365: at 630 d the tree is in leaf with
    // husked nuts; at 535 d its catkins are out; at 400 d it is bare, petioles fallen too.
    Tree t = grow("walnut", 630.0f);
    EXPECT_EQ(t.arch->getPhenologyStage(t.id), PhenologyStage::Reproductive);
    EXPECT_EQ(t.plant().season, 2);
    EXPECT_EQ(flowerObjectCount(*t.arch, t.id), 0u);
    EXPECT_FALSE(t.arch->getPlantObjectIDs(t.id, OrganKind::Fruit).empty());
    Tree spring = grow("walnut", 535.0f);
    EXPECT_GT(flowerObjectCount(*spring.arch, spring.id), 0u);
    Tree winter = grow("walnut", 400.0f);
    EXPECT_EQ(winter.arch->getPhenologyStage(winter.id), PhenologyStage::Dormant);
    EXPECT_EQ(winter.arch->getPlantLeafCount(winter.id), 0u);
    EXPECT_TRUE(winter.arch->getPlantObjectIDs(winter.id, OrganKind::Petiole).empty());
    // In leaf, exactly the petioles that still hold leaflets are drawn.
    std::size_t leafy = 0;
    for (const Shoot& s : t.plant().shoots)
        for (const Phytomer& ph : s.phytomers)
            for (const Petiole& pt : ph.petioles)
                for (const LeafOrgan& l : pt.leaves)
                    if (!l.removed) {
                        ++leafy;
                        break;
                    }
    EXPECT_GT(leafy, 0u);
    EXPECT_EQ(t.arch->getPlantObjectIDs(t.id, OrganKind::Petiole).size(), leafy);
}

TEST(SpeciesTreesWalnut, BuildParameters) {
    for (float h : {0.8f, 1.2f}) {
        Tree t = grow("walnut", 0.0f, {{"trunk_height", h}});
        EXPECT_EQ(t.plant().shoots[0].phytomers.size(), std::size_t(std::lround(h / 0.04f)));
        EXPECT_NEAR(t.plant().shoots[0].phytomers[0].internode.length, 0.04f, 1e-6f);
        for (const Shoot* s : shootsOfType(t.plant(), "scaffold")) {
            EXPECT_GE(s->phytomers.size(), 5u);
            EXPECT_LE(s->phytomers.size(), 7u);
        }
    }
    Tree t = grow("walnut", 0.0f, {{"num_scaffolds", 6}, {"scaffold_angle", 60}});
    const auto scaffolds = shootsOfType(t.plant(), "scaffold");
    EXPECT_EQ(scaffolds.size(), 6u);
    for (const Shoot* s : scaffolds) EXPECT_NEAR(s->insertionAngle, 60.0f, 5.74f);
    // The walnut's scaffold angles run from 25 to 60 degrees (almond's from 20 to 70).
    const Error e = errorOf([] { grow("walnut", 0.0f, {{"scaffold_angle", 20}}); });
    EXPECT_EQ(e.parameter(), "scaffold_angle");
    EXPECT_EQ(e.validRange(), "25 to 60 degrees");
}

// ---- pistachio ---------------------------------------------------------------------------

TEST(SpeciesTreesPistachio, FirstNodeOfEveryShootNeverBranches) {
    Tree t = grow("pistachio", 1000.0f);
    const PlantInstance& p = t.plant();
    int branchesAboveFirst = 0;
    for (const Shoot* s : shootsOfType(p, "proleptic")) {
        for (const VegetativeBud& b : s->phytomers[0].petioles[0].vegetativeBuds)
            EXPECT_EQ(b.state, BudState::Dead);
        for (unsigned c : s->children) {
            EXPECT_GE(p.shoots[c].parentNode, 1);
            ++branchesAboveFirst;
        }
    }
    EXPECT_GT(branchesAboveFirst, 0);
    // Its floral buds are dead from the start, while those of the next node wait for
    // spring (on shoots grown in the first season, before any winter has made them ready).
    Tree young = grow("pistachio", 300.0f);
    int grownShoots = 0;
    for (const Shoot* s : shootsOfType(young.plant(), "proleptic")) {
        if (s->phytomers[0].birth < 165.0) continue;  // a scaffold built with the tree
        ++grownShoots;
        ASSERT_GE(s->phytomers.size(), 2u);
        for (const FloralBud& b : s->phytomers[0].petioles[0].floralBuds)
            EXPECT_EQ(b.state, BudState::Dead);
        for (const FloralBud& b : s->phytomers[1].petioles[0].floralBuds)
            EXPECT_EQ(b.state, BudState::Dormant);
    }
    EXPECT_GT(grownShoots, 0);
}

TEST(SpeciesTreesPistachio, WinterMakesFloralBudsOfOlderNodesReadyAgain) {
    // The same tree before leaf fall (day 360), in winter (400) and in its second summer
    // (630). Floral buds that fruited in the first season are made ready again in winter,
    // except on the three nodes nearest each shoot tip, and fruit again the next summer.
    Tree t = grow("pistachio", 360.0f);
    struct Key {
        unsigned shoot, node, bud;
    };
    std::vector<Key> fruited;
    for (const Shoot* s : shootsOfType(t.plant(), "proleptic"))
        for (unsigned k = 0; k < s->phytomers.size(); ++k) {
            const auto& buds = s->phytomers[k].petioles[0].floralBuds;
            for (unsigned b = 0; b < buds.size(); ++b)
                if (buds[b].stage == FloralStage::Fruit) fruited.push_back({s->id, k, b});
        }
    ASSERT_GT(fruited.size(), 5u);

    t.arch->advanceTime(40.0);  // day 400: dormant
    ASSERT_EQ(t.arch->getPhenologyStage(t.id), PhenologyStage::Dormant);
    for (const Shoot* s : shootsOfType(t.plant(), "proleptic"))
        for (unsigned k = 0; k + 3 < s->phytomers.size(); ++k)
            for (const FloralBud& b : s->phytomers[k].petioles[0].floralBuds) {
                EXPECT_EQ(b.stage, FloralStage::Bud);
                EXPECT_EQ(b.state, BudState::Dormant);
            }

    t.arch->advanceTime(230.0);  // day 630: the old buds flowered again
    int again = 0;
    for (const Key& key : fruited)
        again += flowered(
            t.plant().shoots[key.shoot].phytomers[key.node].petioles[0].floralBuds[key.bud]);
    // Each bud flowers with probability 0.35: about a third of them.
    EXPECT_GT(again, int(fruited.size()) / 8);
    EXPECT_LT(again, int(fruited.size()) * 3 / 4);
    EXPECT_EQ(t.ctx->objectCount(), t.arch->getAllPlantObjectIDs(t.id).size());

    // From fruit on the tree (drawn at day 360) to the next summer in one call: the buds
    // that flowered again take the place of their first-season fruit, whose objects go.
    Tree once = grow("pistachio", 360.0f);
    once.arch->advanceTime(270.0);
    EXPECT_EQ(once.ctx->objectCount(), once.arch->getAllPlantObjectIDs(once.id).size());
    EXPECT_EQ(once.ctx->objectCount(), t.ctx->objectCount());
}

TEST(SpeciesTreesPistachio, ScaffoldsFaceTheCardinalDirections) {
    Tree t = grow("pistachio", 0.0f);
    const PlantInstance& p = t.plant();
    EXPECT_EQ(p.shoots[0].phytomers.size(), 20u);  // 1 m of 5 cm internodes
    std::vector<vec3> dirs;
    for (const Shoot* s : shootsOfType(p, "proleptic")) {
        vec3 g = s->phytomers[0].internode.guide;
        dirs.push_back(glm::normalize(vec3(g.x, g.y, 0.0f)));
        EXPECT_NEAR(s->insertionAngle, 50.0f, 8.6f);
    }
    ASSERT_EQ(dirs.size(), 4u);
    // Two on the top node facing away from each other, two on the node below, at right
    // angles to them (within the trunk's lean of up to 9 degrees).
    EXPECT_LT(glm::dot(dirs[0], dirs[1]), -0.9f);
    EXPECT_LT(glm::dot(dirs[2], dirs[3]), -0.9f);
    EXPECT_LT(std::abs(glm::dot(dirs[0], dirs[2])), 0.35f);
    for (int n : {2, 3}) {
        Tree fewer = grow("pistachio", 0.0f, {{"num_scaffolds", float(n)}});
        EXPECT_EQ(shootsOfType(fewer.plant(), "proleptic").size(), std::size_t(n));
    }
    // At most one scaffold per cardinal direction: more is an error, not ignored.
    const Error e = errorOf([] { grow("pistachio", 0.0f, {{"num_scaffolds", 5}}); });
    EXPECT_EQ(e.parameter(), "num_scaffolds");
    EXPECT_EQ(e.validRange(), "2 to 4");
    Tree low = grow("pistachio", 0.0f, {{"trunk_height", 0.5f}});
    EXPECT_EQ(low.plant().shoots[0].phytomers.size(), 10u);
}
