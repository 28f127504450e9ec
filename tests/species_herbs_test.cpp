// The vegetable and cereal crops of the library (tomato, cherry tomato, capsicum, maize,
// sorghum, wheat, asparagus, butter lettuce): each rule function's effect on a grown plant,
// and the model features they need (callbacks that see node positions, floral buds forced to
// flower or drawn from another shoot type's template).

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <set>

#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;

namespace {

constexpr float kTol = 1e-5f;

// A library plant grown to `age` days.
struct Grown {
    Context ctx;
    PlantArchitecture arch{&ctx};
    unsigned id = 0;
    const PlantInstance& plant() const { return arch.plant(id); }
    const Shoot& shoot(unsigned s) const { return plant().shoots.at(s); }
    int data(ObjectID o, const char* label) const { return ctx.objectDataInt(o, label).value(); }
};

std::unique_ptr<Grown> grow(const std::string& species, float age, std::uint64_t seed = 42) {
    auto g = std::make_unique<Grown>();
    g->arch.setSeed(seed);
    g->arch.loadPlantModelFromLibrary(species);
    g->id = g->arch.buildPlantInstanceFromLibrary(vec3(0.0f), age);
    return g;
}

// The tip leaflet (index 0) of a phytomer's first petiole.
const LeafOrgan& tipLeaf(const Phytomer& ph) {
    for (const LeafOrgan& l : ph.petioles.at(0).leaves)
        if (l.leafletIndex == 0) return l;
    throw std::runtime_error("no tip leaflet");
}

bool flowered(const FloralBud& b) {
    return b.stage == FloralStage::FlowerClosed || b.stage == FloralStage::FlowerOpen ||
           b.stage == FloralStage::Fruit;
}

// Height of the base of internode `k` of shoot `s` above the plant's base.
float nodeBaseHeight(const Grown& g, unsigned s, unsigned k) {
    const vec3 base =
        k == 0 ? (g.shoot(s).parent < 0 ? g.plant().base
                                        : g.arch.getNodePosition(g.id, unsigned(g.shoot(s).parent),
                                                                 unsigned(g.shoot(s).parentNode)))
               : g.arch.getNodePosition(g.id, s, k - 1);
    return base.z - g.plant().base.z;
}

}  // namespace

// ---- tomato ------------------------------------------------------------------------------

TEST(SpeciesHerbsTomato, NoFlowersLowOnTheStemNorOnHighOrderShoots) {
    std::size_t fruit = 0;  // a bud flowers with 0.2: one plant of the two may bear none
    for (std::uint64_t seed : {42u, 7u}) {
        SCOPED_TRACE(seed);
        const auto g = grow("tomato", 80, seed);
        const PlantInstance& p = g->plant();
        bool rank2 = false;
        for (const Shoot& s : p.shoots) {
            for (std::size_t k = 0; k < s.phytomers.size(); ++k) {
                const bool barren = (s.rank == 0 && k < 8) || s.rank > 1;
                for (const Petiole& pt : s.phytomers[k].petioles)
                    for (const FloralBud& b : pt.floralBuds) {
                        if (barren) {
                            EXPECT_FALSE(flowered(b)) << "shoot " << s.id << " node " << k;
                        }
                    }
            }
            if (s.rank > 1) {
                rank2 = true;
                EXPECT_TRUE(s.children.empty()) << "a shoot of rank " << s.rank << " branched";
            }
        }
        EXPECT_TRUE(rank2) << "the 80-day tomato should have shoots of rank 2";
        fruit += g->arch.getPlantObjectIDs(g->id, OrganKind::Fruit).size();
    }
    EXPECT_GT(fruit, 0u);
}

TEST(SpeciesHerbsTomato, EarlyLeavesAndInternodesStartSmaller) {
    const auto g = grow("tomato", 40);
    const Shoot& main = g->shoot(0);
    // Made at emergence: leaves at 50 % (leaflet scale uniform(0.12, 0.18)), the internode at
    // 70 % of the seedling's 0.04 m.
    EXPECT_NEAR(main.phytomers[0].internode.length, 0.7f * 0.04f, kTol);
    EXPECT_GE(tipLeaf(main.phytomers[0]).scale, 0.5f * 0.12f - kTol);
    EXPECT_LE(tipLeaf(main.phytomers[0]).scale, 0.5f * 0.18f + kTol);
    // Made after day 10: full size.
    for (const Phytomer& ph : main.phytomers)
        if (ph.birth >= 10.0) {
            EXPECT_NEAR(ph.internode.length, 0.04f, kTol);
            EXPECT_GE(tipLeaf(ph).scale, 0.12f - kTol);
            EXPECT_LE(tipLeaf(ph).scale, 0.18f + kTol);
        }
}

// The branch count of the 50-day tomato is a binomial draw: the main stem makes a node every
// 2 days, each node's bud breaks 30 days after it forms with probability 0.25, so the buds of
// nodes 0 to 10 (made by day 20) are the only ones due by day 50, and a branch's own buds are
// not due before day 62. Over 200 seeds: every branch is of rank 1 and grows from one of those
// nodes, and the counts follow Binomial(11, 0.25): mean 2.75 within three standard errors
// (0.10 for 200 plants), variance 2.06 within 30 %. (Seeds 1 to 3 alone branch 4, 6 and 4
// times: a 3-plant mean that far above 2.75 turns up in 2.1 % of draws.)
TEST(SpeciesHerbsTomato, BranchesAsItsBudRuleSaysOverManySeeds) {
    constexpr int kSeeds = 200;
    constexpr double n = 11.0, p = 0.25;
    double sum = 0.0, sumSq = 0.0;
    for (std::uint64_t seed = 1; seed <= kSeeds; ++seed) {
        const auto g = grow("tomato", 50, seed);
        int branches = 0;
        for (const Shoot& s : g->plant().shoots) {
            if (s.parent < 0) continue;
            ++branches;
            EXPECT_EQ(s.rank, 1u) << "seed " << seed << " shoot " << s.id;
            EXPECT_LE(s.parentNode, 10) << "seed " << seed << " shoot " << s.id;
        }
        sum += branches;
        sumSq += double(branches) * branches;
    }
    const double mean = sum / kSeeds, variance = sumSq / kSeeds - mean * mean;
    EXPECT_NEAR(mean, n * p, 3.0 * std::sqrt(n * p * (1.0 - p) / kSeeds));
    EXPECT_NEAR(variance, n * p * (1.0 - p), 0.3 * n * p * (1.0 - p));
}

// ---- cherry tomato -------------------------------------------------------------------------

TEST(SpeciesHerbsCherryTomato, NoPruningBeforeDay101) {
    const auto g = grow("cherrytomato", 100);
    for (const Shoot& s : g->plant().shoots)
        for (const Phytomer& ph : s.phytomers)
            for (const Petiole& pt : ph.petioles) {
                EXPECT_GT(pt.length, 0.0f);
                for (const LeafOrgan& l : pt.leaves) EXPECT_FALSE(l.removed);
            }
}

TEST(SpeciesHerbsCherryTomato, LeavesBelowOneMetreAreStrippedFromDay101) {
    const auto g = grow("cherrytomato", 110);
    unsigned stripped = 0, kept = 0;
    for (const Shoot& s : g->plant().shoots)
        for (unsigned k = 0; k < s.phytomers.size(); ++k) {
            const Phytomer& ph = s.phytomers[k];
            // Heights only grow, so a node below 1 m now was below 1 m at the day-110 callback.
            if (ph.birth <= 110.0 && nodeBaseHeight(*g, s.id, k) < 1.0f) {
                ++stripped;
                for (const Petiole& pt : ph.petioles) {
                    EXPECT_EQ(pt.length, 0.0f) << "shoot " << s.id << " node " << k;
                    EXPECT_EQ(pt.radius, 0.0f);
                    for (const LeafOrgan& l : pt.leaves) EXPECT_TRUE(l.removed);
                }
            }
        }
    // The main stem's upper leaves, above 1 m, stay.
    const Shoot& main = g->shoot(0);
    for (unsigned k = 0; k < main.phytomers.size(); ++k)
        if (nodeBaseHeight(*g, 0, k) > 1.2f) {
            ++kept;
            for (const LeafOrgan& l : main.phytomers[k].petioles[0].leaves) EXPECT_FALSE(l.removed);
        }
    EXPECT_GT(stripped, 10u);
    EXPECT_GT(kept, 3u);
    // Stripped leaves and petioles are not drawn.
    const std::size_t leaves = g->arch.getPlantLeafCount(g->id);
    EXPECT_EQ(g->arch.getPlantObjectIDs(g->id, OrganKind::Leaf).size(), leaves);
    for (ObjectID o : g->arch.getPlantObjectIDs(g->id, OrganKind::Petiole)) {
        const Shoot& s = g->shoot(unsigned(g->data(o, "shootID")));
        EXPECT_GT(s.phytomers.at(std::size_t(g->data(o, "node"))).petioles[0].length, 0.0f);
    }
}

TEST(SpeciesHerbsCherryTomato, NoFlowersOrBranchesOnTheFirstEightNodes) {
    const auto g = grow("cherrytomato", 120);
    for (const Shoot& s : g->plant().shoots) {
        for (std::size_t k = 0; k < std::min<std::size_t>(8, s.phytomers.size()); ++k)
            for (const Petiole& pt : s.phytomers[k].petioles)
                for (const FloralBud& b : pt.floralBuds) EXPECT_FALSE(flowered(b));
        if (s.parent >= 0) {
            EXPECT_GE(s.parentNode, 8);
        }
        EXPECT_LE(s.rank, 1u) << "a rank-1 shoot branched";
    }
}

// ---- capsicum ----------------------------------------------------------------------------

TEST(SpeciesHerbsCapsicum, FirstSixMainStemNodesAreBare) {
    for (std::uint64_t seed : {42u, 3u}) {
        SCOPED_TRACE(seed);
        const auto g = grow("capsicum", 100, seed);
        const Shoot& main = g->shoot(0);
        ASSERT_GT(main.phytomers.size(), 10u);
        for (unsigned k = 0; k < main.phytomers.size(); ++k)
            for (const Petiole& pt : main.phytomers[k].petioles) {
                const bool bare = k < 6;
                for (const LeafOrgan& l : pt.leaves) EXPECT_EQ(l.removed, bare) << "node " << k;
                if (bare) {
                    EXPECT_EQ(pt.length, 0.0f);
                    EXPECT_EQ(pt.radius, 0.0f);
                    for (const FloralBud& b : pt.floralBuds) EXPECT_FALSE(flowered(b));
                    for (const VegetativeBud& b : pt.vegetativeBuds) EXPECT_LT(b.childShoot, 0);
                }
            }
        for (unsigned c : main.children) EXPECT_GE(g->shoot(c).parentNode, 6);
        EXPECT_GT(main.children.size(), 0u);
        // Nothing is drawn at those nodes but the stem.
        for (ObjectID o : g->arch.getAllPlantObjectIDs(g->id))
            if (g->data(o, "shootID") == 0 && g->data(o, "node") < 6) {
                EXPECT_EQ(g->ctx.objectDataString(o, "organ"), "internode");
            }
    }
}

TEST(SpeciesHerbsCapsicum, LeavesGrowWithTheNodeAndTheStemStartsShort) {
    const auto g = grow("capsicum", 60);
    const Shoot& main = g->shoot(0);
    for (unsigned k = 0; k < main.phytomers.size(); ++k) {
        const float f = std::min(1.0f, 0.6f + 0.4f * float(k) / 5.0f);
        const float s = tipLeaf(main.phytomers[k]).scale;
        EXPECT_GE(s, 0.12f * f - kTol) << "node " << k;
        EXPECT_LE(s, 0.15f * f + kTol) << "node " << k;
    }
    // The seedling's internode (0.04 m) at 5 %; internodes made from day 15 at full length.
    EXPECT_NEAR(main.phytomers[0].internode.length, 0.05f * 0.04f, kTol);
    for (const Phytomer& ph : main.phytomers)
        if (ph.birth >= 15.0) {
            EXPECT_NEAR(ph.internode.length, 0.04f, kTol);
        }
}

// ---- maize -------------------------------------------------------------------------------

TEST(SpeciesHerbsMaize, EarsAtNodesNineToElevenAndATasselAtTheTip) {
    for (std::uint64_t seed : {42u, 11u}) {
        SCOPED_TRACE(seed);
        const auto g = grow("maize", 50, seed);
        ASSERT_EQ(g->plant().shoots.size(), 1u);
        const Shoot& main = g->shoot(0);
        ASSERT_EQ(main.phytomers.size(), 17u);
        for (unsigned k = 0; k < main.phytomers.size(); ++k) {
            const FloralBud& b = main.phytomers[k].petioles.at(0).floralBuds.at(0);
            if (k >= 9 && k <= 11) {
                EXPECT_EQ(b.stage, FloralStage::Fruit) << "node " << k;
                EXPECT_EQ(b.parametersLabel, "ear");
                // The ear's shank and fruit from the 'ear' type.
                EXPECT_FLOAT_EQ(b.peduncleLength, 0.05f);
                EXPECT_FLOAT_EQ(b.peduncleRadius, 0.01f);
                EXPECT_FLOAT_EQ(b.pedunclePitch, 5.0f);
                ASSERT_EQ(b.flowers.size(), 1u);
                EXPECT_FLOAT_EQ(b.flowers[0].fruitScale, 0.2f);
            } else {
                EXPECT_EQ(b.stage, FloralStage::Removed) << "node " << k;
            }
        }
        ASSERT_EQ(main.terminalFloralBuds.size(), 1u);
        const FloralBud& tassel = main.terminalFloralBuds[0];
        EXPECT_EQ(tassel.stage, FloralStage::Fruit);
        EXPECT_TRUE(tassel.parametersLabel.empty());
        EXPECT_FLOAT_EQ(tassel.peduncleLength, 0.14f);
        EXPECT_FLOAT_EQ(tassel.flowers.at(0).fruitScale, 0.25f);
        // Drawn: fruit only at nodes 9, 10, 11 (ears) and 16 (the tassel).
        std::set<int> nodes;
        for (ObjectID o : g->arch.getPlantObjectIDs(g->id, OrganKind::Fruit))
            nodes.insert(g->data(o, "node"));
        EXPECT_EQ(nodes, (std::set<int>{9, 10, 11, 16}));
    }
}

TEST(SpeciesHerbsMaize, LeavesTaperAtTheBaseAndTheTop) {
    const auto g = grow("maize", 50);
    const Shoot& main = g->shoot(0);
    const int n = main.maxNodes;
    for (int k = 0; k < n; ++k) {
        float s = 1.0f;
        if (k <= 5)
            s = std::min(1.0f, 0.7f + 0.3f * float(k) / 5.0f);
        else if (k >= n - 5)
            s = std::min(1.0f, 0.65f + 0.35f * float(n - k) / 3.0f);
        EXPECT_NEAR(tipLeaf(main.phytomers[std::size_t(k)]).scale, 0.6f * s, kTol) << "node " << k;
    }
    // The culm's internodes are the seedling's 0.08 m (the base stem sets its shoot's length),
    // shortened the same way up to node 5.
    EXPECT_NEAR(main.phytomers[0].internode.length, 0.08f * 0.7f, kTol);
    EXPECT_NEAR(main.phytomers[3].internode.length, 0.08f * 0.88f, kTol);
    EXPECT_NEAR(main.phytomers[8].internode.length, 0.08f, kTol);
}

// ---- sorghum and wheat ---------------------------------------------------------------------

TEST(SpeciesHerbsSorghum, FlagLeafStandsMoreUpright) {
    for (std::uint64_t seed : {42u, 5u}) {
        SCOPED_TRACE(seed);
        const auto g = grow("sorghum", 50, seed);
        const Shoot& main = g->shoot(0);
        ASSERT_EQ(main.phytomers.size(), 16u);
        for (unsigned k = 0; k < 16; ++k) {
            const float pitch = main.phytomers[k].petioles.at(0).pitch;
            // The flag leaf: the last node's 5 degrees and the rule's 25.
            const float lo = k == 15 ? 30.0f : -40.0f, hi = k == 15 ? 30.0f : -20.0f;
            EXPECT_GE(pitch, lo - kTol) << "node " << k;
            EXPECT_LE(pitch, hi + kTol) << "node " << k;
            const float s = std::min(1.0f, 0.7f + 0.3f * float(k) / 5.0f);
            EXPECT_NEAR(tipLeaf(main.phytomers[k]).scale, 0.6f * s, kTol);
        }
        EXPECT_EQ(g->arch.getPlantObjectIDs(g->id, OrganKind::Fruit).empty(), false);  // the head
    }
}

TEST(SpeciesHerbsWheat, EarlyLeavesAndInternodesStartSmaller) {
    const auto g = grow("wheat", 50);
    const Shoot& main = g->shoot(0);
    ASSERT_EQ(main.phytomers.size(), 20u);
    for (unsigned k = 0; k < 20; ++k) {
        const float s = std::min(1.0f, 0.7f + 0.3f * float(k) / 5.0f);
        EXPECT_NEAR(tipLeaf(main.phytomers[k]).scale, 0.22f * s, kTol) << "node " << k;
        // The culm's internodes are the seedling's 0.025 m (the base stem sets its shoot's length).
        EXPECT_NEAR(main.phytomers[k].internode.length, 0.025f * s, kTol);
    }
    ASSERT_EQ(main.terminalFloralBuds.size(), 1u);
    EXPECT_EQ(main.terminalFloralBuds[0].stage, FloralStage::Fruit);  // the spike
}

// ---- asparagus ---------------------------------------------------------------------------

TEST(SpeciesHerbsAsparagus, FirstThreeNodesMakeNoBranchAndSmallCladodes) {
    const auto g = grow("asparagus", 20);
    const PlantInstance& p = g->plant();
    ASSERT_GT(p.shoots.size(), 1u);
    for (const Shoot& s : p.shoots) {
        if (s.parent >= 0) {
            EXPECT_GE(s.parentNode, 3);
        }
        for (unsigned k = 0; k < s.phytomers.size(); ++k)
            for (const LeafOrgan& l : s.phytomers[k].petioles.at(0).leaves) {
                // Five cladodes: the tip one and two pairs at 0.9 and 0.81 of its size.
                const float lo = 0.81f * 0.018f, hi = 0.02f;
                const float f = k <= 2 ? 0.6f : 1.0f;
                EXPECT_GE(l.scale, f * lo - kTol);
                EXPECT_LE(l.scale, f * hi + kTol);
            }
    }
}

TEST(SpeciesHerbsAsparagus, CladodesAreSlenderSpines) {
    const auto g = grow("asparagus", 20);
    const std::vector<ObjectID> leaves = g->arch.getPlantObjectIDs(g->id, OrganKind::Leaf);
    ASSERT_EQ(leaves.size(), g->arch.getPlantLeafCount(g->id));
    for (ObjectID o : leaves) {
        const ObjectView v = g->ctx.object(o);
        EXPECT_EQ(v.triangleCount(), 16u);  // 2 segments of a 3-sided prism, its point and base
        AABB box;
        for (const vec3& q : v.positions) box.add(q);
        EXPECT_LE(glm::length(box.extent()), 0.021f);  // at most 2 cm long
    }
}

// ---- butter lettuce ------------------------------------------------------------------------

TEST(SpeciesHerbsButterLettuce, OuterLeavesDroopInnerLeavesStandUp) {
    const auto g = grow("butterlettuce", 50);
    for (const Shoot& s : g->plant().shoots) {
        ASSERT_EQ(s.maxNodes, 25);
        for (unsigned k = 0; k < s.phytomers.size(); ++k)
            EXPECT_NEAR(s.phytomers[k].petioles.at(0).leaves.at(0).pitch,
                        10.0f - 60.0f * float(25 - int(k)) / 25.0f, kTol);
    }
}

// ---- every crop: no build parameters -------------------------------------------------------

TEST(SpeciesHerbsAll, LoadWithTheirRulesAndRejectBuildParameters) {
    // Rules per crop: creation rules on the first shoot type, and cherry tomato's daily pruning.
    const std::map<std::string, std::size_t> rules{
        {"tomato", 4},  {"cherrytomato", 5}, {"capsicum", 4},  {"maize", 5},
        {"sorghum", 2}, {"wheat", 1},        {"asparagus", 1}, {"butterlettuce", 1}};
    for (const auto& [name, count] : rules) {
        SCOPED_TRACE(name);
        Context ctx;
        PlantArchitecture arch(&ctx);
        arch.loadPlantModelFromLibrary(name);
        const std::vector<std::string> labels = arch.listShootTypeLabels();
        ASSERT_FALSE(labels.empty());
        const PhytomerParameters pp =
            arch.getCurrentShootParameters(labels.front()).phytomer_parameters;
        EXPECT_EQ(pp.node_rules.size(), count);
        EXPECT_EQ(pp.phytomer_creation_function, "");
        EXPECT_THROW(arch.buildPlantInstanceFromLibrary(vec3(0.0f), 10, {{"trunk_height", 1.0f}}),
                     Error);
    }
    Context ctx;
    PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("cherrytomato");
    const NodeRule pruning =
        arch.getCurrentShootParameters("mainstem").phytomer_parameters.node_rules.back();
    EXPECT_EQ(pruning.when, NodeRuleTime::Daily);
    EXPECT_EQ(pruning.age_min, 101.0f);
    EXPECT_EQ(pruning.height_below, 1.0f);
    EXPECT_TRUE(pruning.remove_leaves);
}

// ---- the model features these rules use ---------------------------------------------------

namespace {

ShootParameters floweringShoot() {
    ShootParameters s;
    auto& pp = s.phytomer_parameters;
    pp.internode.pitch = 0.0f;
    pp.internode.max_vegetative_buds_per_petiole = 0;
    pp.internode.max_floral_buds_per_petiole = 1;
    pp.peduncle.length = 0.02f;
    pp.inflorescence.flower_prototype_scale = 0.01f;
    s.max_nodes = 8;
    s.determinate_shoot_growth = false;  // keeps growing while it flowers
    s.phyllochron_min = 1.0f;
    s.internode_length_max = 0.03f;
    s.flower_bud_break_probability = 0.0f;  // only forced buds flower
    return s;
}

struct Bed {
    Context ctx;
    PlantArchitecture arch{&ctx};
    unsigned plant(const ShootParameters& type) {
        arch.defineShootType("main", type);
        PhenologyParameters ph;
        ph.time_to_flower_opening = 2.0f;  // open flowers 2 days after dormancy break
        arch.setDefaultPhenology(ph);
        const unsigned id = arch.addPlantInstance(vec3(0.0f), 0.0f);
        arch.addBaseStemShoot(id, {1, AxisRotation{}, {0.002f, 0.03f, 0.01f, 0.01f}, 0.0f, "main"});
        return id;
    }
};

}  // namespace

TEST(SpeciesHerbsModel, ForcedFloralBudsFlowerDrawnFromTheirOwnType) {
    Bed b;
    b.arch.registerPhytomerCreationFunction("force_node_3", [](PhytomerCreationContext& c) {
        if (c.nodeIndex != 3) return;
        for (Petiole& p : c.phytomer.petioles)
            for (FloralBud& fb : p.floralBuds) {
                fb.state = BudState::Active;
                fb.parametersLabel = "big";
            }
    });
    ShootParameters big = floweringShoot();
    big.phytomer_parameters.peduncle.length = 0.123f;
    big.phytomer_parameters.inflorescence.flower_prototype_scale = 0.05f;
    b.arch.defineShootType("big", big);
    ShootParameters main = floweringShoot();
    main.phytomer_parameters.phytomer_creation_function = "force_node_3";
    const unsigned id = b.plant(main);
    b.arch.advanceTime(id, 20);
    const Shoot& s = b.arch.plant(id).shoots[0];
    ASSERT_EQ(s.phytomers.size(), 8u);
    for (unsigned k = 0; k < 8; ++k) {
        const FloralBud& fb = s.phytomers[k].petioles[0].floralBuds[0];
        if (k == 3) {
            EXPECT_EQ(fb.stage, FloralStage::FlowerOpen);
            EXPECT_FLOAT_EQ(fb.peduncleLength, 0.123f);
            EXPECT_FLOAT_EQ(fb.flowers.at(0).flowerScale, 0.05f);
        } else {
            EXPECT_EQ(fb.stage, FloralStage::Removed) << "node " << k;  // probability 0
        }
    }
    // The one flower drawn is the big type's: 5 cm.
    const std::vector<ObjectID> flowers = b.arch.getPlantObjectIDs(id, OrganKind::FlowerOpen);
    ASSERT_FALSE(flowers.empty());
    AABB box;
    for (ObjectID o : flowers) {
        EXPECT_EQ(b.ctx.objectDataInt(o, "node").value(), 3);
        for (const vec3& q : b.ctx.object(o).positions) box.add(q);
    }
    EXPECT_GT(glm::length(box.extent()), 0.03f);
}

TEST(SpeciesHerbsModel, AFloralBudNamingNoShootTypeIsAnError) {
    Bed b;
    b.arch.registerPhytomerCreationFunction("bad_label", [](PhytomerCreationContext& c) {
        for (Petiole& p : c.phytomer.petioles)
            for (FloralBud& fb : p.floralBuds) {
                fb.state = BudState::Active;
                fb.parametersLabel = "nonesuch";
            }
    });
    ShootParameters main = floweringShoot();
    main.phytomer_parameters.phytomer_creation_function = "bad_label";
    try {
        const unsigned id = b.plant(main);  // drawing the plant already looks the type up
        b.arch.advanceTime(id, 10);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_EQ(e.parameter(), "shoot_type_label");
        EXPECT_EQ(e.value(), "nonesuch");
    }
}

TEST(SpeciesHerbsModel, CallbacksSeeTheNodePositionsOfTheDay) {
    // Records each node's base on the last whole day; grown in one call and in daily calls.
    auto run = [](bool daily) {
        Bed b;
        auto seen = std::make_shared<std::map<unsigned, vec3>>();
        b.arch.registerPhytomerCallbackFunction(
            "record", [seen](PhytomerCallbackContext& c) { (*seen)[c.nodeIndex] = c.nodeBase; });
        ShootParameters main = floweringShoot();
        main.phytomer_parameters.phytomer_callback_function = "record";
        main.phytomer_parameters.internode.pitch = 15.0f;  // a zig-zag stem
        main.elongation_rate_max = 0.05f;                  // still elongating on day 10
        const unsigned id = b.plant(main);
        if (daily)
            for (int d = 0; d < 10; ++d) b.arch.advanceTime(id, 1);
        else
            b.arch.advanceTime(id, 10);
        // The geometry at day 10 is the state the day-10 callbacks saw.
        const unsigned n = b.arch.getShootNodeCount(id, 0);
        EXPECT_EQ(seen->size(), n);
        for (unsigned k = 0; k < n; ++k) {
            const vec3 expected = k == 0 ? vec3(0.0f) : b.arch.getNodePosition(id, 0, k - 1);
            EXPECT_NEAR(glm::length(seen->at(k) - expected), 0.0f, 1e-6f) << "node " << k;
        }
        return *seen;
    };
    const auto once = run(false), daily = run(true);
    ASSERT_EQ(once.size(), daily.size());
    for (const auto& [k, v] : once) EXPECT_EQ(v, daily.at(k)) << "node " << k;
}
