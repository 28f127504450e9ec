// Growth and phenology: each rule checked with parameters chosen so the answer is known.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "plantarch/Error.h"
#include "plantarch/PlantArchitecture.h"

using namespace plantarch;

namespace {

// Vertical, deterministic shoot: phyllochron 2 days, no branching, no flowers.
ShootParameters growingShoot() {
    ShootParameters s;
    s.phytomer_parameters.internode.pitch = 0.0f;
    s.phytomer_parameters.internode.phyllotactic_angle = 180.0f;
    s.phytomer_parameters.internode.radius_initial = 0.002f;
    s.phytomer_parameters.internode.max_vegetative_buds_per_petiole = 0;
    s.phytomer_parameters.internode.max_floral_buds_per_petiole = 0;
    s.phytomer_parameters.petiole.length = 0.04f;
    s.phytomer_parameters.leaf.prototype_scale = 0.05f;
    s.max_nodes = 30;
    s.phyllochron_min = 2.0f;
    s.elongation_rate_max = 0.1f;
    s.internode_length_max = 0.03f;
    return s;
}

struct Garden {
    Context ctx;
    PlantArchitecture arch{&ctx};

    unsigned plant(const ShootParameters& type, unsigned nodes = 1, float pitch = 0.0f,
                   const vec3& base = vec3(0.0f), float lengthScale = 0.01f) {
        arch.defineShootType("main", type);
        const unsigned id = arch.addPlantInstance(base, 0.0f);
        ShootSpec spec;
        spec.phytomers = nodes;
        spec.baseRotation.pitch = pitch;
        spec.size.internodeRadius = 0.002f;
        spec.size.internodeLengthMax = 0.03f;
        spec.size.internodeLengthScale = lengthScale;
        spec.size.leafScale = lengthScale;
        spec.shootType = "main";
        arch.addBaseStemShoot(id, spec);
        return id;
    }
    const PlantInstance& state(unsigned id) const { return arch.plant(id); }
};

// A parent type whose every axillary bud may grow a one-node "child" shoot (defined in `g`).
ShootParameters branchingParent(Garden& g, int maxNodes, float breakProbability, float breakTime) {
    ShootParameters s = growingShoot();
    s.max_nodes = maxNodes;
    s.phytomer_parameters.internode.max_vegetative_buds_per_petiole = 1;
    s.vegetative_bud_break_probability_min = breakProbability;
    s.vegetative_bud_break_time = breakTime;
    s.child_shoot_types = {{"child", 1.0f}};
    ShootParameters child = growingShoot();
    child.max_nodes = 1;
    g.arch.defineShootType("child", child);
    return s;
}

// A growing shoot of `maxNodes` nodes whose every node has one floral bud that flowers and
// sets fruit.
ShootParameters floweringShoot(int maxNodes) {
    ShootParameters s = growingShoot();
    s.max_nodes = maxNodes;
    s.phytomer_parameters.internode.max_floral_buds_per_petiole = 1;
    s.flower_bud_break_probability = 1.0f;
    s.fruit_set_probability = 1.0f;
    return s;
}

std::vector<vec3> allPositions(const Context& ctx) {
    std::vector<vec3> out;
    ctx.forEachObject([&](const ObjectView& v) {
        out.insert(out.end(), v.positions.begin(), v.positions.end());
    });
    return out;
}

// Objects of the plant's flowers, closed and open.
std::size_t flowerObjectCount(const PlantArchitecture& arch, unsigned plantID) {
    return arch.getPlantObjectIDs(plantID, OrganKind::FlowerClosed).size() +
           arch.getPlantObjectIDs(plantID, OrganKind::FlowerOpen).size();
}

}  // namespace

TEST(Growth, NewPhytomerEveryPhyllochron) {
    Garden g;
    const unsigned p = g.plant(growingShoot());
    for (int day = 1; day <= 20; ++day) {
        g.arch.advanceTime(1.0f);
        // A phytomer at days 2, 4, 6, ...: 1 + floor(day / 2) in all.
        EXPECT_EQ(g.arch.getShootNodeCount(p, 0), unsigned(1 + day / 2)) << "day " << day;
    }
    EXPECT_DOUBLE_EQ(g.arch.getPlantAge(p), 20.0);
}

TEST(Growth, MaxNodesStopsTheShoot) {
    ShootParameters s = growingShoot();
    s.max_nodes = 5;
    Garden g;
    const unsigned p = g.plant(s);
    g.arch.advanceTime(100.0f);
    EXPECT_EQ(g.arch.getShootNodeCount(p, 0), 5u);
}

// max_nodes_per_season limits the nodes a shoot's apex adds in a season: the nodes it is
// built with, or the one a shoot from a bud starts with, are not among them; a phytomer
// appended by hand is. With 3 a season: a stem built with 2 nodes grows to 5; with one more
// appended by hand on day 1 (its season began on day 0), to 5 as well; a shoot from a bud (1
// node) to 4.
TEST(Growth, MaxNodesPerSeasonCountsTheNodesTheApexAdds) {
    ShootParameters s = growingShoot();
    s.max_nodes_per_season = 3;
    for (bool appended : {false, true}) {
        Garden g;
        const unsigned p = g.plant(s, 2);
        g.arch.advanceTime(1.0f);
        if (appended) {
            PhytomerSize size;
            size.internodeRadius = 0.002f;
            size.internodeLengthMax = 0.03f;
            g.arch.appendPhytomerToShoot(p, 0, s.phytomer_parameters, size);
        }
        g.arch.advanceTime(49.0f);
        EXPECT_EQ(g.arch.getShootNodeCount(p, 0), 5u) << (appended ? "appended" : "built");
    }
    Garden g;
    ShootParameters parent = branchingParent(g, 1, 1.0f, 0.0f);
    ShootParameters child = s;
    g.arch.defineShootType("child", child);
    const unsigned p = g.plant(parent);
    g.arch.advanceTime(50.0f);
    ASSERT_EQ(g.arch.getShootCount(p), 2u);
    EXPECT_EQ(g.arch.getShootNodeCount(p, 0), 1u);
    EXPECT_EQ(g.arch.getShootNodeCount(p, 1), 4u);
}

TEST(Growth, InternodeElongatesLinearlyToFullLength) {
    Garden g;
    const unsigned p = g.plant(growingShoot());
    // The first phytomer starts at 1% and gains 10% of its full length per day.
    for (float day : {1.0f, 3.0f, 5.0f, 9.0f, 9.9f, 12.0f}) {
        g.arch.advanceTime(day - float(g.arch.getPlantAge(p)));
        const Phytomer& ph = g.state(p).shoots[0].phytomers[0];
        const float expected = std::min(1.0f, 0.01f + 0.1f * day);
        EXPECT_NEAR(ph.internodeFraction, expected, 1e-5f) << "day " << day;
        const AABB box = g.ctx.objectBoundingBox(ph.internode.object);
        EXPECT_NEAR(box.max.z - box.min.z, 0.03f * expected, 1e-5f) << "day " << day;
        // Petioles and leaves grow at the same relative rate.
        EXPECT_NEAR(ph.leafFraction, expected, 1e-5f);
    }
}

namespace {
// A parent of 8 nodes whose every axillary bud breaks at once, so child internode lengths can
// be read off along the parent. The lengths and their decay are the child type's own; the
// parent's (0.2 m, no decay) must play no part.
std::vector<float> childLengths(float decay) {
    Garden g;
    ShootParameters s = branchingParent(g, 8, 1.0f, 0.0f);
    s.phyllochron_min = 1.0f;
    s.internode_length_max = 0.2f;
    s.internode_length_min = 0.2f;
    s.internode_length_decay_rate = 0.0f;
    ShootParameters child = growingShoot();
    child.max_nodes = 1;
    child.internode_length_max = 0.05f;
    child.internode_length_min = 0.01f;
    child.internode_length_decay_rate = decay;
    g.arch.defineShootType("child", child);
    const unsigned p = g.plant(s, 8);  // all 8 nodes exist before the buds break
    g.arch.advanceTime(0.0f);
    std::vector<float> lengths(8, -1.0f);
    for (const Shoot& sh : g.state(p).shoots)
        if (sh.parent == 0) lengths[std::size_t(sh.parentNode)] = sh.internodeLengthMax;
    return lengths;
}
}  // namespace

TEST(Growth, BasitonicChildInternodesShortenUpTheParent) {
    const std::vector<float> l = childLengths(-0.01f);
    // 0.05 at the base, 0.01 less per node, never below 0.01.
    const float expected[] = {0.05f, 0.04f, 0.03f, 0.02f, 0.01f, 0.01f, 0.01f, 0.01f};
    for (int k = 0; k < 8; ++k) EXPECT_NEAR(l[std::size_t(k)], expected[k], 1e-6f) << "node " << k;
}

TEST(Growth, AcrotonicChildInternodesLengthenTowardTheTip) {
    const std::vector<float> l = childLengths(0.01f);
    const float expected[] = {0.01f, 0.01f, 0.01f, 0.01f, 0.02f, 0.03f, 0.04f, 0.05f};
    for (int k = 0; k < 8; ++k) EXPECT_NEAR(l[std::size_t(k)], expected[k], 1e-6f) << "node " << k;
}

TEST(Growth, ConstantChildInternodeLengthWithoutDecay) {
    for (float l : childLengths(0.0f)) EXPECT_NEAR(l, 0.05f, 1e-6f);
}

// A petiole stands at least 5 degrees off its stem, and those of a shoot's last node at 5
// degrees: with petiole pitch uniform(-3, 3) and 60 on a shoot of 6 nodes, every petiole but the
// last node's is at 5 or 60; the last node's at 5 either way.
TEST(Growth, PetiolesStandAtLeastFiveDegreesOffTheStemAndTheLastNodesAtFive) {
    for (float pitch : {0.0f, 60.0f}) {
        ShootParameters s = growingShoot();
        s.max_nodes = 6;
        s.phytomer_parameters.petiole.pitch =
            pitch == 0.0f ? RandomFloat::uniform(-3.0f, 3.0f) : RandomFloat(pitch);
        Garden g;
        const unsigned p = g.plant(s);
        g.arch.advanceTime(20.0f);
        const Shoot& sh = g.state(p).shoots[0];
        ASSERT_EQ(sh.phytomers.size(), 6u);
        for (std::size_t k = 0; k < 6; ++k)
            EXPECT_FLOAT_EQ(sh.phytomers[k].petioles[0].pitch,
                            k == 5 ? 5.0f : std::max(pitch, 5.0f))
                << "node " << k;
    }
}

TEST(Growth, ShootsFromBudsTakeTheirOwnTypesInsertionAngle) {
    // The parent type's angle (95: flat) must not apply; the child type's does: 30 at the
    // parent's tip and 20 more per node below it, at most 90 (specification, child shoot
    // insertion angle). The parent's 6 nodes all stand when the buds break at age 0, so node
    // k lies 5 - k nodes below the tip: 30, 50, 70, then 90 from node 2 down.
    Garden g;
    ShootParameters s = branchingParent(g, 6, 1.0f, 0.0f);
    s.insertion_angle_tip = 95.0f;
    s.insertion_angle_decay_rate = 0.0f;
    ShootParameters child = growingShoot();
    child.max_nodes = 1;
    child.insertion_angle_tip = 30.0f;
    child.insertion_angle_decay_rate = 20.0f;
    g.arch.defineShootType("child", child);
    const unsigned p = g.plant(s, 6);
    g.arch.advanceTime(0.0f);
    const float expected[] = {90.0f, 90.0f, 90.0f, 70.0f, 50.0f, 30.0f};
    unsigned children = 0;
    for (const Shoot& sh : g.state(p).shoots) {
        if (sh.parent != 0) continue;
        ++children;
        const float want = expected[sh.parentNode];
        EXPECT_NEAR(sh.insertionAngle, want, 1e-4f) << "node " << sh.parentNode;
        // The parent stands vertical, so the child's first internode leaves at that zenith.
        const vec3 axis = sh.phytomers[0].internode.guide;
        EXPECT_NEAR(std::acos(std::clamp(axis.z, -1.0f, 1.0f)) * 180.0f / std::numbers::pi_v<float>,
                    want, 1e-3f)
            << "node " << sh.parentNode;
    }
    EXPECT_EQ(children, 6u);
}

namespace {

// The specification's curvature: each new internode turns its zenith angle by
// -s (1 - cos z) L C degrees, z from the vertical, s = 1 when the tip points below the
// horizontal and 0.5 otherwise; the zenith stays within 0 to 180 degrees.
void expectGravitropism(float startZenith, float curvature) {
    SCOPED_TRACE("start " + std::to_string(startZenith) + " curvature " +
                 std::to_string(curvature));
    ShootParameters s = growingShoot();
    s.gravitropic_curvature = curvature;  // degrees per metre
    s.max_nodes = 15;
    Garden g;
    const unsigned p = g.plant(s, 1, startZenith);
    g.arch.advanceTime(28.0f);
    const Shoot& sh = g.state(p).shoots[0];
    ASSERT_EQ(sh.phytomers.size(), 15u);
    const double deg = std::numbers::pi / 180.0;
    double zenith = startZenith;
    EXPECT_NEAR(std::acos(double(sh.phytomers[0].internode.guide.z)) / deg, zenith, 1e-3);
    for (std::size_t k = 1; k < sh.phytomers.size(); ++k) {
        const double sfac = zenith > 90.0 + 1e-3 ? 1.0 : 0.5;
        zenith -= sfac * (1.0 - std::cos(zenith * deg)) * 0.03 * curvature;
        zenith = std::clamp(zenith, 0.0, 180.0);
        const double measured = std::acos(double(sh.phytomers[k].internode.guide.z)) / deg;
        EXPECT_NEAR(measured, zenith, 1e-2) << "node " << k;
    }
}

}  // namespace

TEST(Growth, GravitropismFollowsTheEquationFromEveryStart) {
    expectGravitropism(90.0f, 300.0f);   // horizontal: s = 0.5 from the first node
    expectGravitropism(150.0f, 300.0f);  // below the horizontal: s = 1 until it rises past it
    expectGravitropism(175.0f, 100.0f);  // almost straight down
    expectGravitropism(30.0f, -300.0f);  // negative curvature bends it down, past the horizontal
}

// The numbers of the equation, worked by hand: from 150 degrees with 300 degrees per metre and
// 3 cm internodes, the first turn is 1 * (1 + cos 30) * 0.03 * 300 = 16.79 degrees (it would be
// half that if the tip were taken as pointing up).
TEST(Growth, GravitropismBelowTheHorizontalTurnsAtFullRate) {
    ShootParameters s = growingShoot();
    s.gravitropic_curvature = 300.0f;
    s.max_nodes = 2;
    Garden g;
    const unsigned p = g.plant(s, 1, 150.0f);
    g.arch.advanceTime(10.0f);
    const Shoot& sh = g.state(p).shoots[0];
    ASSERT_EQ(sh.phytomers.size(), 2u);
    EXPECT_NEAR(sh.phytomers[1].internode.gravitropicTurn, 16.79f, 0.01f);
    const float zenith = std::acos(sh.phytomers[1].internode.guide.z) * 180.0f / 3.14159265f;
    EXPECT_NEAR(zenith, 150.0f - 16.79f, 0.01f);
}

TEST(Growth, RandomWalkHasZeroMeanAndTheEquationsVariance) {
    ShootParameters s = growingShoot();
    s.tortuosity = 10.0f;  // degrees per sqrt(m)
    s.max_nodes = 11;
    Garden g;
    g.arch.defineShootType("main", s);
    const int plants = 600;
    std::vector<double> zen, yaw;
    for (int i = 0; i < plants; ++i) {
        const unsigned id = g.arch.addPlantInstance(vec3(float(i), 0, 0), 0.0f);
        g.arch.addBaseStemShoot(id, {1, {}, {0.002f, 0.03f, 1, 1}, 0, "main"});
    }
    g.arch.advanceTime(20.0f);
    for (unsigned id : g.arch.getAllPlantIDs()) {
        const Internode& last = g.state(id).shoots[0].phytomers.back().internode;
        zen.push_back(last.walkZenith);
        yaw.push_back(last.walkYaw);
    }
    // theta_{t+1} = (1 - L/2) theta_t + T N(0, L), from 0 over 10 steps.
    const double L = 0.03, a = 1.0 - L / 2.0, T = 10.0;
    double var = 0.0;
    for (int j = 0; j < 10; ++j) var += T * T * L * std::pow(a, 2 * j);
    for (const auto* v : {&zen, &yaw}) {
        const double mean = std::accumulate(v->begin(), v->end(), 0.0) / double(v->size());
        double s2 = 0.0;
        for (double x : *v) s2 += (x - mean) * (x - mean);
        s2 /= double(v->size() - 1);
        EXPECT_NEAR(mean, 0.0, 5.0 * std::sqrt(var / plants));
        // Sample variance of a normal: relative standard error sqrt(2 / (n - 1)).
        EXPECT_NEAR(s2 / var, 1.0, 5.0 * std::sqrt(2.0 / (plants - 1)));
    }
}

TEST(Growth, GirthFollowsDownstreamLeafArea) {
    ShootParameters s = growingShoot();
    s.girth_area_factor = 50.0f;  // cm^2 per m^2
    s.max_nodes = 6;
    Garden g;
    const unsigned p = g.plant(s);
    g.arch.advanceTime(40.0f);
    const Shoot& sh = g.state(p).shoots[0];
    // Downstream of internode k: every leaf at nodes k..end, read from the geometry.
    for (std::size_t k = 0; k < sh.phytomers.size(); ++k) {
        double area = 0.0;
        for (std::size_t j = k; j < sh.phytomers.size(); ++j)
            for (const Petiole& pt : sh.phytomers[j].petioles)
                for (const LeafOrgan& l : pt.leaves) area += g.ctx.objectArea(l.objects[0]);
        const double r = std::sqrt(50.0 * area * 1e-4 / std::numbers::pi);
        EXPECT_NEAR(sh.phytomers[k].internode.radius, std::max(r, 0.002), 1e-6) << "node " << k;
    }
    EXPECT_GT(sh.phytomers[0].internode.radius, sh.phytomers[5].internode.radius);
    // Girth never shrinks when leaves go.
    const float before = sh.phytomers[0].internode.radius;
    g.arch.removePlantLeaves(p);
    g.arch.advanceTime(5.0f);
    EXPECT_EQ(g.state(p).shoots[0].phytomers[0].internode.radius, before);
}

TEST(Growth, ZeroGirthFactorLocksTheRadius) {
    Garden g;
    const unsigned p = g.plant(growingShoot());
    g.arch.advanceTime(30.0f);
    for (const Phytomer& ph : g.state(p).shoots[0].phytomers)
        EXPECT_FLOAT_EQ(ph.internode.radius, ph.radiusInitial);
}

TEST(Growth, BudBreakFractionMatchesProbability) {
    Garden g;
    ShootParameters s = branchingParent(g, 1, 0.3f, 3.0f);
    s.vegetative_bud_break_probability_decay_rate = 0.0f;
    g.arch.defineShootType("main", s);
    const int n = 2000;
    for (int i = 0; i < n; ++i) {
        const unsigned id = g.arch.addPlantInstance(vec3(float(i), 0, 0), 0.0f);
        g.arch.addBaseStemShoot(id, {1, {}, {0.002f, 0.03f, 1, 1}, 0, "main"});
    }
    g.arch.advanceTime(2.9f);  // not yet: buds break after 3 days
    int broken = 0;
    for (unsigned id : g.arch.getAllPlantIDs()) broken += int(g.arch.getShootCount(id)) - 1;
    EXPECT_EQ(broken, 0);
    g.arch.advanceTime(0.2f);
    for (unsigned id : g.arch.getAllPlantIDs()) broken += int(g.arch.getShootCount(id)) - 1;
    const double sd = std::sqrt(n * 0.3 * 0.7);
    EXPECT_NEAR(broken, n * 0.3, 5 * sd);
}

// Fraction of 1500 six-node shoots branching at each node, for a basitonic decay of -0.25
// with a minimum of 0.1, on buds that need a winter (or not).
std::vector<int> basitonicBranchesPerNode(bool needsWinter) {
    Garden g;
    ShootParameters s = branchingParent(g, 6, 0.1f, 0.0f);
    s.vegetative_bud_break_probability_decay_rate = -0.25f;
    s.growth_requires_dormancy = needsWinter;
    g.arch.defineShootType("main", s);
    const int n = 1500;
    for (int i = 0; i < n; ++i) {
        const unsigned id = g.arch.addPlantInstance(vec3(float(i), 0, 0), 0.0f);
        g.arch.addBaseStemShoot(id, {6, {}, {0.002f, 0.03f, 1, 1}, 0, "main"});
    }
    g.arch.advanceTime(0.0f);
    std::vector<int> perNode(6, 0);
    for (unsigned id : g.arch.getAllPlantIDs())
        for (const Shoot& sh : g.state(id).shoots)
            if (sh.parent == 0) perNode[std::size_t(sh.parentNode)]++;
    return perNode;
}

TEST(Growth, BudBreakProbabilityDecaysFromTheBaseAfterWinter) {
    // Basitonic buds sorted as dormancy breaks: probability 1 at node 0, -0.25 per node up,
    // at least 0.1.
    const std::vector<int> perNode = basitonicBranchesPerNode(true);
    const int n = 1500;
    const double p[] = {1.0, 0.75, 0.5, 0.25, 0.1, 0.1};
    for (int k = 0; k < 6; ++k)
        EXPECT_NEAR(perNode[std::size_t(k)], n * p[k], 5 * std::sqrt(n * p[k] * (1 - p[k])) + 1e-9)
            << "node " << k;
}

TEST(Growth, BudBreakProbabilityIsTheMinimumWithoutWinterWhenBasitonic) {
    // Shoots that grow on without a winter take the minimum, 0.1, at every node.
    const std::vector<int> perNode = basitonicBranchesPerNode(false);
    const int n = 1500;
    for (int k = 0; k < 6; ++k)
        EXPECT_NEAR(perNode[std::size_t(k)], n * 0.1, 5 * std::sqrt(n * 0.1 * 0.9)) << "node " << k;
}

TEST(Growth, BudBreakProbabilityWithoutWinterIsTheMaximumAtTheFirstNodeOnly) {
    // Acrotonic (decay 0.25 per node below the tip, minimum 0.1, maximum 1), no winter: a new
    // node every day up to 6, buds breaking 2.5 days after they form. The first bud formed at
    // the tip of a one-node shoot: 1; every later bud the minimum, 0.1. (Counted from the tip
    // when it breaks it would be 0.5, 0.5, 0.5, 0.5, 0.75, 1; against the final 6-node shoot
    // 0.1, 0.1, 0.25, 0.5, 0.75, 1.)
    Garden g;
    ShootParameters s = branchingParent(g, 6, 0.1f, 2.5f);
    s.phyllochron_min = 1.0f;
    s.vegetative_bud_break_probability_decay_rate = 0.25f;
    g.arch.defineShootType("main", s);
    const int n = 1500;
    for (int i = 0; i < n; ++i) {
        const unsigned id = g.arch.addPlantInstance(vec3(float(i), 0, 0), 0.0f);
        g.arch.addBaseStemShoot(id, {1, {}, {0.002f, 0.03f, 1, 1}, 0, "main"});
    }
    g.arch.advanceTime(10.0f);
    std::vector<int> perNode(6, 0);
    for (unsigned id : g.arch.getAllPlantIDs()) {
        ASSERT_EQ(g.state(id).shoots[0].phytomers.size(), 6u);
        for (const Shoot& sh : g.state(id).shoots)
            if (sh.parent == 0) perNode[std::size_t(sh.parentNode)]++;
    }
    const double p[] = {1.0, 0.1, 0.1, 0.1, 0.1, 0.1};
    for (int k = 0; k < 6; ++k)
        EXPECT_NEAR(perNode[std::size_t(k)], n * p[k], 5 * std::sqrt(n * p[k] * (1 - p[k])) + 1e-9)
            << "node " << k;
}

namespace {
struct Stages {
    unsigned buds = 0, closed = 0, open = 0, fruit = 0;
    bool operator==(const Stages&) const = default;
};
// The plant's axillary floral buds by stage (one flower per peduncle).
Stages stagesOf(const PlantInstance& plant) {
    Stages n;
    for (const Shoot& sh : plant.shoots)
        for (const Phytomer& ph : sh.phytomers)
            for (const Petiole& pt : ph.petioles)
                for (const FloralBud& fb : pt.floralBuds) switch (fb.stage) {
                        case FloralStage::Bud:
                            ++n.buds;
                            break;
                        case FloralStage::FlowerClosed:
                            ++n.closed;
                            break;
                        case FloralStage::FlowerOpen:
                            ++n.open;
                            break;
                        case FloralStage::Fruit:
                            ++n.fruit;
                            break;
                        default:
                            break;
                    }
    return n;
}
std::ostream& operator<<(std::ostream& o, const Stages& n) {
    return o << n.buds << " buds, " << n.closed << " closed, " << n.open << " open, " << n.fruit
             << " fruit";
}
}  // namespace

// Each floral bud keeps its own clock (specification, phenological transitions and
// reproductive growth): closed time_to_flower_initiation after its clock starts, open
// time_to_flower_opening later, fruit time_to_fruit_set after that. The clock of a bud made
// while the plant is dormant starts at dormancy break, that of a bud made in the season when
// it is made. Dormancy breaks on day 5; node 0 was built dormant on day 0, nodes 1 to 3 are
// made on days 7, 9 and 11 (phyllochron 2 after dormancy break). With initiation 20, opening
// 4 and fruit set 6: closed on days 25, 27, 29, 31; open on 29, 31, 33, 35; fruit on 35, 37,
// 39, 41.
TEST(Growth, PhenologyStagesOnTheirDays) {
    ShootParameters s = floweringShoot(4);
    s.determinate_shoot_growth = false;
    Garden g;
    PhenologyParameters ph;
    ph.time_to_dormancy_break = 5;
    ph.time_to_flower_initiation = 20;
    ph.time_to_flower_opening = 4;
    ph.time_to_fruit_set = 6;
    ph.time_to_fruit_maturity = 10;
    g.arch.setDefaultPhenology(ph);
    const unsigned p = g.plant(s);
    auto count = [&](OrganKind kind) { return g.arch.getPlantObjectIDs(p, kind).size(); };
    auto at = [&](double day) {
        g.arch.advanceTime(float(day - g.arch.getPlantAge(p)));
        return stagesOf(g.state(p));
    };
    EXPECT_EQ(at(4.9), (Stages{1, 0, 0, 0}));
    EXPECT_EQ(g.arch.getPhenologyStage(p), PhenologyStage::Dormant);
    EXPECT_EQ(g.arch.getShootNodeCount(p, 0), 1u);
    at(5.0);  // dormancy breaks
    EXPECT_EQ(g.arch.getPhenologyStage(p), PhenologyStage::Vegetative);
    EXPECT_EQ(at(24.9), (Stages{4, 0, 0, 0}));
    EXPECT_EQ(flowerObjectCount(g.arch, p), 0u);
    EXPECT_EQ(at(25.0), (Stages{3, 1, 0, 0}));
    EXPECT_EQ(g.arch.getPhenologyStage(p), PhenologyStage::Reproductive);
    EXPECT_GT(count(OrganKind::FlowerClosed), 0u);
    EXPECT_EQ(count(OrganKind::FlowerOpen), 0u);
    for (ObjectID id : g.arch.getPlantObjectIDs(p, OrganKind::FlowerClosed))
        EXPECT_EQ(g.ctx.objectDataString(id, "organ"), "flower_closed");
    EXPECT_EQ(at(28.9), (Stages{2, 2, 0, 0}));
    EXPECT_EQ(at(29.0), (Stages{1, 2, 1, 0}));
    for (ObjectID id : g.arch.getPlantObjectIDs(p, OrganKind::FlowerOpen))
        EXPECT_EQ(g.ctx.objectDataString(id, "organ"), "flower_open");
    EXPECT_EQ(at(34.9), (Stages{0, 1, 3, 0}));
    EXPECT_EQ(count(OrganKind::Fruit), 0u);
    EXPECT_EQ(at(35.0), (Stages{0, 0, 3, 1}));
    EXPECT_EQ(count(OrganKind::Fruit), 0u);  // just set: of size 0, no geometry yet
    // Fruit grow to full size over the maturity time.
    const FloralBud& bud = g.state(p).shoots[0].phytomers[0].petioles[0].floralBuds[0];
    EXPECT_EQ(bud.stage, FloralStage::Fruit);
    EXPECT_FLOAT_EQ(bud.fruitGrowth, 0.0f);
    at(40.0);
    EXPECT_NEAR(bud.fruitGrowth, 0.5f, 1e-6f);
    EXPECT_GT(count(OrganKind::Fruit), 0u);
    EXPECT_EQ(at(41.0), (Stages{0, 0, 0, 4}));
    at(50.0);
    EXPECT_FLOAT_EQ(bud.fruitGrowth, 1.0f);
}

// A plant built by hand with 5 nodes on day 0 grows a node every 2 days; dormancy breaks at
// once. Every bud's clock starts when its node is made, so node k (made on day 2 (k - 4) for
// k >= 5, on day 0 below) opens 12 days after (initiation off) and sets fruit 8 days after
// that: the first open flowers on day 12 (the five built nodes), the first fruit on day 20,
// and a node made on day 30 opens on day 42, not as soon as it is made.
TEST(Growth, EachFloralBudFlowersOnItsOwnClock) {
    ShootParameters s = floweringShoot(40);
    s.determinate_shoot_growth = false;
    Garden g;
    PhenologyParameters ph;
    ph.time_to_flower_initiation = -1;
    ph.time_to_flower_opening = 12;
    ph.time_to_fruit_set = 8;
    ph.time_to_fruit_maturity = 10;
    g.arch.setDefaultPhenology(ph);
    const unsigned p = g.plant(s, 5);
    auto at = [&](double day) {
        g.arch.advanceTime(float(day - g.arch.getPlantAge(p)));
        return stagesOf(g.state(p));
    };
    // Day 11.9: nodes 0-4 (day 0) and 5-9 (days 2-10) are buds.
    EXPECT_EQ(at(11.9), (Stages{10, 0, 0, 0}));
    // Day 12: the five built nodes open; node 10 is made.
    EXPECT_EQ(at(12.0), (Stages{6, 0, 5, 0}));
    // Day 19.9: nodes 11-13 made on days 14-18; nodes 5-7 (days 2-6) open on days 14-18.
    EXPECT_EQ(at(19.9), (Stages{6, 0, 8, 0}));
    // Day 20: the built nodes set fruit, node 8 (day 8) opens; nodes 9-14 (days 10-20) wait.
    EXPECT_EQ(at(20.0), (Stages{6, 0, 4, 5}));
    // Day 41.9: nodes made on days 0-28 have opened (day 28 + 12 = 40 <= 41.9); those made on
    // days 30-40 (nodes 19-24) are still buds; fruit on the nodes made on days 0-20.
    const Stages day41 = at(41.9);
    EXPECT_EQ(day41.buds, 6u) << day41;
    EXPECT_EQ(day41.fruit, 5u + 10u) << day41;
    EXPECT_EQ(day41.open, 4u) << day41;
}

// A determinate shoot stops at flowering, an indeterminate one grows on. With a node every
// 2 days from day 0 and flowers opening on day 10: nodes on days 0, 2, 4, 6 and 8 (the
// flowering on day 10 comes before that day's node), so 5; without determinacy a node every 2
// days to day 30 (the end of the step included), so 16.
TEST(Growth, DeterminateShootStopsAtFlowering) {
    for (bool determinate : {true, false}) {
        SCOPED_TRACE(determinate ? "determinate" : "indeterminate");
        ShootParameters s = growingShoot();
        s.max_nodes = 50;
        s.phytomer_parameters.internode.max_floral_buds_per_petiole = 1;
        s.flower_bud_break_probability = 1.0f;
        s.determinate_shoot_growth = determinate;
        Garden g;
        PhenologyParameters ph;
        ph.time_to_flower_opening = 10;  // no closed stage: open flowers on day 10
        g.arch.setDefaultPhenology(ph);
        const unsigned p = g.plant(s);
        g.arch.advanceTime(30.0f);
        EXPECT_EQ(g.arch.getShootNodeCount(p, 0), determinate ? 5u : 16u);
        EXPECT_TRUE(g.state(p).shoots[0].flowering);
    }
}

// A determinate shoot turns reproductive when its first floral bud comes due, even if that bud
// fails to flower: it stops (5 nodes, as above) and its vegetative buds still waiting die, so
// no branch grows from the buds that would have broken on day 12 and after. Indeterminate, it
// grows on and every bud of nodes 0 to 9 (made by day 18, breaking 12 days later) branches.
TEST(Growth, DeterminateShootEndsAsItsFirstFloralBudComesDueEvenIfItFails) {
    for (bool determinate : {true, false}) {
        SCOPED_TRACE(determinate ? "determinate" : "indeterminate");
        Garden g;
        ShootParameters s = branchingParent(g, 50, 1.0f, 12.0f);
        s.phytomer_parameters.internode.max_floral_buds_per_petiole = 1;
        s.flower_bud_break_probability = 0.0f;  // every floral bud fails
        s.determinate_shoot_growth = determinate;
        PhenologyParameters ph;
        ph.time_to_flower_opening = 10;
        g.arch.setDefaultPhenology(ph);
        const unsigned p = g.plant(s);
        g.arch.advanceTime(30.0f);
        const PlantInstance& plant = g.state(p);
        EXPECT_EQ(plant.shoots[0].phytomers.size(), determinate ? 5u : 16u);
        EXPECT_EQ(flowerObjectCount(g.arch, p), 0u);
        std::size_t branches = 0;
        for (const Shoot& sh : plant.shoots) branches += sh.parent == 0 ? 1u : 0u;
        EXPECT_EQ(branches, determinate ? 0u : 10u);
    }
}

namespace {
// Seasons of 30 days after winters of 10: the first from day 10 to 40, the second from day 50.
void tenDayWinters(Garden& g, bool evergreen = false) {
    PhenologyParameters ph;
    ph.time_to_dormancy_break = 10;
    ph.time_to_senescence = 30;
    ph.evergreen = evergreen;
    g.arch.setDefaultPhenology(ph);
}
unsigned perennial(Garden& g, bool evergreen) {
    ShootParameters s = growingShoot();
    s.max_nodes = 40;
    s.max_nodes_per_season = 5;
    tenDayWinters(g, evergreen);
    return g.plant(s);
}
}  // namespace

TEST(Growth, TwoSeasonsOfAPerennial) {
    Garden g;
    const unsigned p = perennial(g, false);
    g.arch.advanceTime(9.0f);
    EXPECT_EQ(g.arch.getShootNodeCount(p, 0), 1u);  // dormant until day 10
    g.arch.advanceTime(30.0f);                      // day 39: season 1, 5 new nodes at most
    EXPECT_EQ(g.arch.getShootNodeCount(p, 0), 6u);
    EXPECT_GT(g.arch.getPlantLeafCount(p), 0u);
    g.arch.advanceTime(1.0f);  // day 40: senescence, leaves fall
    EXPECT_EQ(g.arch.getPhenologyStage(p), PhenologyStage::Dormant);
    EXPECT_EQ(g.arch.getPlantLeafCount(p), 0u);
    EXPECT_TRUE(g.arch.getPlantObjectIDs(p, OrganKind::Leaf).empty());
    g.arch.advanceTime(9.0f);  // day 49: still winter
    EXPECT_EQ(g.arch.getShootNodeCount(p, 0), 6u);
    g.arch.advanceTime(11.0f);  // day 60: season 2 began on day 50
    EXPECT_EQ(g.arch.getPhenologyStage(p), PhenologyStage::Vegetative);
    EXPECT_EQ(g.state(p).season, 2);
    EXPECT_EQ(g.arch.getShootNodeCount(p, 0), 11u);  // 5 more
    EXPECT_GT(g.arch.getPlantLeafCount(p), 0u);      // new leaves only
    EXPECT_EQ(g.arch.getPlantLeafCount(p), 5u);
}

// A bud that needs no winter breaks vegetative_bud_break_time after it is made (the
// specification's bud break); one made while the plant is dormant, whose time passes in the
// winter, breaks as dormancy ends. Three nodes built on day 0, dormancy breaking on day 20:
// with a break time of 5 days the three buds break on day 20, with 30 days on day 30.
TEST(Growth, BudsMadeWhileDormantBreakWhenTheirTimeHasCome) {
    for (float breakTime : {5.0f, 30.0f}) {
        SCOPED_TRACE("break time " + std::to_string(breakTime));
        Garden g;
        ShootParameters s = branchingParent(g, 3, 1.0f, breakTime);
        PhenologyParameters ph;
        ph.time_to_dormancy_break = 20;
        g.arch.setDefaultPhenology(ph);
        const unsigned p = g.plant(s, 3);
        const double day = std::max(20.0, double(breakTime));
        g.arch.advanceTime(float(day) - 0.1f);
        EXPECT_EQ(g.arch.getShootCount(p), 1u);
        g.arch.advanceTime(0.1f);
        EXPECT_EQ(g.arch.getShootCount(p), 4u);
        EXPECT_EQ(g.arch.getPlantLeafCount(p), 6u);  // the parent's 3 and a leaf per child
    }
}

// A perennial's buds still waiting when the season ends break as the next season begins
// (their vegetative_bud_break_time since they were made has passed), and the new shoots
// carry the season's leaves. Dormancy breaks on day 10, the season ends on day 40 and the
// next begins on day 50. The parent's node 0 (built on day 0) and the nodes made on days 12,
// 14, 16, 18 and 20 (5 a season) have buds breaking 25 days after they are made: node 0 on
// day 25 (its time counts from day 0), the next two on days 37 and 39, the last three
// (days 41, 43, 45) as season 2 begins on day 50.
TEST(Growth, APerennialsWaitingBudsGrowLeafyShootsInTheNextSeason) {
    Garden g;
    ShootParameters s = branchingParent(g, 40, 1.0f, 25.0f);
    s.max_nodes_per_season = 5;
    tenDayWinters(g);
    const unsigned p = g.plant(s);
    g.arch.advanceTime(24.9f);
    EXPECT_EQ(g.arch.getShootCount(p), 1u);
    g.arch.advanceTime(0.1f);  // day 25
    EXPECT_EQ(g.arch.getShootCount(p), 2u);
    g.arch.advanceTime(14.5f);  // day 39.5
    EXPECT_EQ(g.arch.getShootCount(p), 4u);
    EXPECT_EQ(g.arch.getPlantLeafCount(p), 6u + 3u);
    g.arch.advanceTime(10.4f);  // day 49.9: winter, bare
    EXPECT_EQ(g.arch.getPhenologyStage(p), PhenologyStage::Dormant);
    EXPECT_EQ(g.arch.getShootCount(p), 4u);
    EXPECT_EQ(g.arch.getPlantLeafCount(p), 0u);
    g.arch.advanceTime(1.1f);  // day 51: season 2
    EXPECT_EQ(g.state(p).season, 2);
    EXPECT_EQ(g.arch.getShootCount(p), 7u);
    // The leaves of season 2 so far: one on each new shoot (the parent's next node comes on
    // day 52).
    EXPECT_EQ(g.arch.getPlantLeafCount(p), 3u);
    for (const Shoot& sh : g.state(p).shoots)
        if (sh.parent == 0 && sh.parentNode >= 3) {
            EXPECT_DOUBLE_EQ(sh.phytomers[0].birth, 50.0) << "node " << sh.parentNode;
            EXPECT_FALSE(sh.phytomers[0].petioles[0].leaves[0].removed);
        }
}

// Buds that need a winter (proleptic shoots) break as the next season begins when their
// vegetative_bud_break_time since they were made has passed, so the shoot they grow from
// stands as it did through the winter: an acrotonic child's internode length and its insertion
// angle count the bud's nodes below that shoot's tip. A bud made too late for that breaks when
// its time comes. The plant is built dormant (its first winter) with node 0; season 1 runs from
// day 10 to 40, season 2 from day 50; the parent makes nodes 1 to 14 on days 12, 14, ..., 38
// (the one due on day 40 falls to the season's end); buds break 25 days after they are made.
TEST(Growth, BudsNeedingAWinterBreakAsTheSeasonBeginsOnLastSeasonsShoot) {
    Garden g;
    ShootParameters s = branchingParent(g, 40, 1.0f, 25.0f);
    s.growth_requires_dormancy = true;
    s.max_nodes_per_season = 20;
    ShootParameters child = growingShoot();
    child.max_nodes = 1;
    child.internode_length_max = 0.05f;
    child.internode_length_min = 0.01f;
    child.internode_length_decay_rate = 0.005f;
    child.insertion_angle_tip = 30.0f;
    child.insertion_angle_decay_rate = 2.0f;
    g.arch.defineShootType("child", child);
    tenDayWinters(g);
    const unsigned p = g.plant(s);
    g.arch.advanceTime(49.9f);
    // Only node 0's bud has broken (day 25): the dormancy it was built in was its winter.
    EXPECT_EQ(g.arch.getShootCount(p), 2u);
    ASSERT_EQ(g.state(p).shoots[0].phytomers.size(), 15u);
    g.arch.advanceTime(0.2f);  // day 50.1
    // The buds of nodes 1 to 7 (made on days 12 to 24) broke as season 2 began.
    EXPECT_EQ(g.arch.getShootCount(p), 9u);
    g.arch.advanceTime(16.0f);  // day 66.1: the rest, 25 days after their nodes were made
    const PlantInstance& plant = g.state(p);
    ASSERT_EQ(plant.shoots.size(), 16u);
    const Shoot& parent = plant.shoots[0];
    for (const Shoot& c : plant.shoots) {
        if (c.parent != 0) continue;
        const int k = c.parentNode;
        SCOPED_TRACE("node " + std::to_string(k));
        const double made = parent.phytomers[std::size_t(k)].birth;
        const double broke = k == 0 ? 25.0 : std::max(50.0, made + 25.0);
        EXPECT_DOUBLE_EQ(c.phytomers[0].birth, broke);
        // The parent's tip when the bud broke: its most distal node made by then.
        int tip = 0;
        for (const Phytomer& node : parent.phytomers)
            if (node.birth <= broke) ++tip;
        const int fromTip = tip - 1 - k;
        if (k >= 1 && k <= 7) {
            EXPECT_EQ(fromTip, 14 - k);  // last season's tip, node 14
        }
        EXPECT_NEAR(c.phytomers[0].internode.length,
                    std::max(0.01f, 0.05f - 0.005f * float(fromTip)), 1e-6f);
        EXPECT_NEAR(c.insertionAngle, std::min(90.0f, 30.0f + 2.0f * float(fromTip)), 1e-4f);
    }
}

TEST(Growth, EvergreenKeepsItsLeavesThroughDormancy) {
    Garden g;
    const unsigned p = perennial(g, true);
    g.arch.advanceTime(41.0f);
    EXPECT_EQ(g.arch.getPhenologyStage(p), PhenologyStage::Dormant);
    EXPECT_EQ(g.arch.getPlantLeafCount(p), 6u);
    g.arch.advanceTime(5.0f);
    EXPECT_EQ(g.arch.getShootNodeCount(p, 0), 6u);  // but it does not grow
}

TEST(Growth, LeavesFallAtTheirMaximumLifespan) {
    ShootParameters s = growingShoot();
    Garden g;
    PhenologyParameters ph;
    ph.max_leaf_lifespan = 9.0f;
    g.arch.setDefaultPhenology(ph);
    const unsigned p = g.plant(s);
    g.arch.advanceTime(20.0f);
    // Leaves made on days 0, 2, ..., 20; those older than 9 days (days 0..10) have fallen.
    EXPECT_EQ(g.arch.getPlantLeafCount(p), 5u);
}

TEST(Growth, CustomFunctionsAreCalledWithTheirArguments) {
    ShootParameters s = growingShoot();
    s.max_nodes = 6;
    s.phytomer_parameters.phytomer_creation_function = "halve_late_leaves";
    s.phytomer_parameters.phytomer_callback_function = "count";
    Garden g;
    std::vector<std::tuple<unsigned, int, int, double>> created;
    int calls = 0;
    std::vector<double> callbackAges;
    g.arch.registerPhytomerCreationFunction("halve_late_leaves", [&](PhytomerCreationContext& c) {
        created.emplace_back(c.nodeIndex, c.parentNodeIndex, c.shootMaxNodes, c.plantAge);
        if (c.nodeIndex >= 3)
            for (Petiole& pt : c.phytomer.petioles)
                for (LeafOrgan& l : pt.leaves) l.scale *= 0.5f;
    });
    g.arch.registerPhytomerCallbackFunction("count", [&](PhytomerCallbackContext& c) {
        ++calls;
        if (c.nodeIndex == 0) callbackAges.push_back(c.plantAge);
    });
    const unsigned p = g.plant(s);
    g.arch.advanceTime(4.5f);
    g.arch.advanceTime(7.5f);
    ASSERT_EQ(created.size(), 6u);
    for (unsigned k = 0; k < 6; ++k) {
        EXPECT_EQ(std::get<0>(created[k]), k);
        EXPECT_EQ(std::get<1>(created[k]), -1);
        EXPECT_EQ(std::get<2>(created[k]), 6);
        EXPECT_DOUBLE_EQ(std::get<3>(created[k]), 2.0 * k);
    }
    const auto& phs = g.state(p).shoots[0].phytomers;
    EXPECT_FLOAT_EQ(phs[4].petioles[0].leaves[0].scale, 0.025f);
    EXPECT_FLOAT_EQ(phs[1].petioles[0].leaves[0].scale, 0.05f);
    // Callbacks once per phytomer on every whole day: days 1..12.
    EXPECT_EQ(callbackAges, (std::vector<double>{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12}));
    EXPECT_GT(calls, 12);
    // An unregistered name is an error when the type is defined.
    ShootParameters bad = growingShoot();
    bad.phytomer_parameters.phytomer_creation_function = "nope";
    EXPECT_THROW(g.arch.defineShootType("bad", bad), Error);
}

TEST(Growth, StepSizeInvariance) {
    // A branching, flowering, randomised plant grown 60 days in different splits.
    auto grow = [](const std::vector<float>& steps) {
        ShootParameters s = growingShoot();
        s.max_nodes = 20;
        s.phyllochron_min = 1.5f;
        s.tortuosity = 5.0f;
        s.gravitropic_curvature = 50.0f;
        s.girth_area_factor = 20.0f;
        s.phytomer_parameters.internode.phyllotactic_angle = RandomFloat::uniform(130, 150);
        s.phytomer_parameters.petiole.pitch = RandomFloat::normal(50, 8);
        s.phytomer_parameters.internode.max_vegetative_buds_per_petiole = 1;
        s.phytomer_parameters.internode.max_floral_buds_per_petiole = 1;
        s.vegetative_bud_break_probability_min = 0.3f;
        s.vegetative_bud_break_probability_max = 0.6f;
        s.vegetative_bud_break_probability_decay_rate = -0.25f;
        s.vegetative_bud_break_time = RandomFloat::uniform(3, 9);
        s.flower_bud_break_probability = 0.6f;
        s.fruit_set_probability = 0.5f;
        s.determinate_shoot_growth = false;
        s.phytomer_parameters.inflorescence.flowers_per_peduncle = RandomInt::uniform(1, 3);
        s.phytomer_parameters.inflorescence.flower_offset = 0.3f;
        s.phytomer_parameters.leaf.leaves_per_petiole = 3;
        s.phytomer_parameters.leaf.leaflet_offset = 0.3f;
        PhenologyParameters ph;
        ph.time_to_flower_initiation = 25;
        ph.time_to_flower_opening = 4;
        ph.time_to_fruit_set = 4;
        ph.time_to_fruit_maturity = 15;
        ph.max_leaf_lifespan = 40;
        auto g = std::make_unique<Garden>();
        g->arch.setSeed(11);
        g->arch.setDefaultPhenology(ph);
        const unsigned p = g->plant(s);
        for (float d : steps) g->arch.advanceTime(d);
        struct Result {
            std::size_t shoots, leaves, flowers, fruit, objects, triangles;
            std::vector<vec3> positions;
        };
        return Result{
            g->arch.getShootCount(p),      g->arch.getPlantLeafCount(p),
            flowerObjectCount(g->arch, p), g->arch.getPlantObjectIDs(p, OrganKind::Fruit).size(),
            g->ctx.objectCount(),          g->ctx.triangleCount(),
            allPositions(g->ctx)};
    };
    const auto once = grow({60.0f});
    EXPECT_GT(once.shoots, 3u);
    EXPECT_GT(once.fruit, 0u);
    std::vector<std::vector<float>> splits = {std::vector<float>(60, 1.0f),
                                              {7.0f, 13.0f, 40.0f},
                                              std::vector<float>(120, 0.5f),
                                              std::vector<float>(600, 0.1f),
                                              {0.0f, 59.0f, 0.25f, 0.75f}};
    for (const auto& steps : splits) {
        const auto other = grow(steps);
        EXPECT_EQ(other.shoots, once.shoots);
        EXPECT_EQ(other.leaves, once.leaves);
        EXPECT_EQ(other.flowers, once.flowers);
        EXPECT_EQ(other.fruit, once.fruit);
        EXPECT_EQ(other.objects, once.objects);
        ASSERT_EQ(other.triangles, once.triangles);
        // Object IDs may be issued in another order; compare the sorted positions.
        auto a = once.positions, b = other.positions;
        auto less = [](const vec3& x, const vec3& y) {
            return std::tie(x.x, x.y, x.z) < std::tie(y.x, y.y, y.z);
        };
        ASSERT_EQ(a.size(), b.size());
        std::sort(a.begin(), a.end(), less);
        std::sort(b.begin(), b.end(), less);
        double worst = 0.0;
        for (std::size_t i = 0; i < a.size(); ++i)
            worst = std::max(worst, double(glm::length(a[i] - b[i])));
        EXPECT_LT(worst, 1e-5) << steps.size() << " steps";
    }
}

TEST(Growth, InvalidTimeStepsAreErrors) {
    Garden g;
    const unsigned p = g.plant(growingShoot());
    EXPECT_THROW(g.arch.advanceTime(-1.0f), Error);
    EXPECT_THROW(g.arch.advanceTime(std::nanf("")), Error);
    EXPECT_THROW(g.arch.advanceTime(99u, 1.0f), Error);
    PhenologyParameters bad;
    bad.max_leaf_lifespan = -3;
    EXPECT_THROW(g.arch.setPlantPhenologicalThresholds(p, bad), Error);
}

TEST(Growth, ProgressCallbackReportsEachPlantAndDaysWithinIt) {
    Garden g;
    g.arch.defineShootType("main", growingShoot());
    for (int i = 0; i < 4; ++i) {
        const unsigned id = g.arch.addPlantInstance(vec3(float(i), 0, 0), 0.0f);
        g.arch.addBaseStemShoot(id, {1, {}, {0.002f, 0.03f, 1, 1}, 0, "main"});
    }
    std::vector<double> fractions;
    g.arch.setProgressCallback([&](std::string_view stage, double f) {
        EXPECT_EQ(stage, "growing");
        fractions.push_back(f);
    });
    g.arch.advanceTime(5.0);
    // Each plant's end (a quarter each), and days within each plant before it, increasing.
    ASSERT_FALSE(fractions.empty());
    EXPECT_EQ(fractions.back(), 1.0);
    for (double end : {0.25, 0.5, 0.75})
        EXPECT_NE(std::find(fractions.begin(), fractions.end(), end), fractions.end()) << end;
    EXPECT_GT(fractions.size(), 4u);
    for (std::size_t i = 1; i < fractions.size(); ++i) EXPECT_LT(fractions[i - 1], fractions[i]);
}

TEST(Growth, WithNoFlowerStagesFruitFollowDormancyBreak) {
    ShootParameters s = floweringShoot(3);
    Garden g;
    PhenologyParameters ph;
    ph.time_to_flower_initiation = -1;
    ph.time_to_flower_opening = -1;
    ph.time_to_fruit_set = 12;
    ph.time_to_fruit_maturity = 8;
    g.arch.setDefaultPhenology(ph);
    const unsigned p = g.plant(s);
    g.arch.advanceTime(11.9);
    EXPECT_TRUE(g.arch.getPlantObjectIDs(p, OrganKind::Fruit).empty());
    EXPECT_EQ(flowerObjectCount(g.arch, p), 0u);
    g.arch.advanceTime(0.1);  // day 12: fruit (of size 0, no geometry yet), never a flower
    bool fruit = false;
    for (const Phytomer& phy : g.state(p).shoots[0].phytomers)
        for (const FloralBud& fb : phy.petioles[0].floralBuds)
            fruit = fruit || fb.stage == FloralStage::Fruit;
    EXPECT_TRUE(fruit);
    EXPECT_EQ(flowerObjectCount(g.arch, p), 0u);
    g.arch.advanceTime(0.1);
    EXPECT_FALSE(g.arch.getPlantObjectIDs(p, OrganKind::Fruit).empty());
    EXPECT_EQ(flowerObjectCount(g.arch, p), 0u);
}
