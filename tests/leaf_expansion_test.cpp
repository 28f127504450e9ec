// Leaf expansion (src/growth/leaf_expansion.h, docs/growth.md "elongation"): the closed form
// is the stepped law f(n+1) = r (f(n) + rate step) at whole steps, a leaf of the nominal size
// grows linearly, a smaller one levels off at rate step r / (1 - r), and a grown plant's
// leaves follow it whatever the number of growth calls.

#include "growth/leaf_expansion.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "plantarch/PlantArchitecture.h"
#include "plantarch/SpeciesIO.h"

using namespace plantarch;

namespace {

// The law stepped by hand: each step adds rate x step of the full size and measures the
// length against the nominal size.
double stepped(double f0, double rate, double ratio, double step, int steps) {
    double f = f0;
    for (int i = 0; i < steps && f < 1.0; ++i) f = std::min(1.0, ratio * (f + rate * step));
    return f;
}

}  // namespace

TEST(LeafExpansion, ClosedFormIsTheSteppedLawAtWholeSteps) {
    for (const double ratio : {0.5, 0.7, 0.8, 0.95, 1.0, 1.1, 1.5})
        for (const double step : {1.0, 2.0, 3.0})
            for (int n = 0; n <= 30; ++n) {
                SCOPED_TRACE(testing::Message()
                             << "ratio " << ratio << " step " << step << " n " << n);
                EXPECT_NEAR(leafFractionAt(0.01f, 0.1f, n * step, float(ratio), step),
                            stepped(0.01, 0.1, ratio, step, n), 2e-6);
            }
}

TEST(LeafExpansion, NominalLeavesGrowLinearlySmallerOnesLevelOff) {
    // r = 1: f0 + rate age, full at (1 - f0) / rate days.
    EXPECT_FLOAT_EQ(leafFractionAt(0.01f, 0.1f, 4.5, 1.0f, 2.0), 0.46f);
    EXPECT_FLOAT_EQ(leafFractionAt(0.01f, 0.1f, 9.9, 1.0f, 2.0), 1.0f);
    EXPECT_FLOAT_EQ(leafFractionAt(0.01f, 0.1f, 500.0, 1.0f, 2.0), 1.0f);
    // r = 0.5, rate 0.1, step 2: levels off at 0.2 of full size, never reaching it.
    EXPECT_NEAR(leafFractionAt(0.01f, 0.1f, 200.0, 0.5f, 2.0), 0.2, 1e-6);
    // r = 0.8: 0.8 of full size; r = 0.9: the level 1.8 is past full size, so it gets there.
    EXPECT_NEAR(leafFractionAt(0.01f, 0.1f, 400.0, 0.8f, 2.0), 0.8, 1e-5);
    EXPECT_FLOAT_EQ(leafFractionAt(0.01f, 0.1f, 400.0, 0.9f, 2.0), 1.0f);
    // A leaf drawn larger than the nominal size is full sooner than a nominal one.
    EXPECT_GT(leafFractionAt(0.01f, 0.1f, 6.0, 1.2f, 2.0),
              leafFractionAt(0.01f, 0.1f, 6.0, 1.0f, 2.0));
    // Between steps the fraction rises without a jump or a dip.
    float previous = 0.0f;
    for (int i = 0; i <= 400; ++i) {
        const float f = leafFractionAt(0.01f, 0.1f, i * 0.05, 0.7f, 2.0);
        EXPECT_GE(f, previous) << i;
        previous = f;
    }
    // Built full grown, a leaf stays full grown.
    EXPECT_FLOAT_EQ(leafFractionAt(1.0f, 0.1f, 10.0, 0.5f, 2.0), 1.0f);
}

TEST(LeafExpansion, SizeRatioIsTheTipLeafOverTheNominalSize) {
    Phytomer ph;
    ph.petioles.resize(1);
    LeafOrgan tip, side;
    tip.leafletIndex = 0;
    tip.scale = 0.06f;
    side.leafletIndex = 1;
    side.scale = 0.03f;
    ph.petioles[0].leaves = {side, tip};
    // Constant nominal size: plain ratio. uniform(a, b): the mean of 1 / P is ln(b/a)/(b-a).
    EXPECT_FLOAT_EQ(leafSizeRatio(ph, nominalReciprocal(RandomFloat(0.12f))), 0.5f);
    EXPECT_NEAR(leafSizeRatio(ph, nominalReciprocal(RandomFloat::uniform(0.12f, 0.18f))),
                0.06 * std::log(1.5) / 0.06, 1e-6);
    // An even count has a pair at the tip.
    ph.petioles[0].leaves = {side};
    EXPECT_FLOAT_EQ(leafSizeRatio(ph, nominalReciprocal(RandomFloat(0.12f))), 0.25f);
    // No leaf, a zero-size leaf or a nominal size that can be 0: linear growth.
    ph.petioles[0].leaves.clear();
    EXPECT_FLOAT_EQ(leafSizeRatio(ph, nominalReciprocal(RandomFloat(0.12f))), 1.0f);
    tip.scale = 0.0f;
    ph.petioles[0].leaves = {tip};
    EXPECT_FLOAT_EQ(leafSizeRatio(ph, nominalReciprocal(RandomFloat(0.12f))), 1.0f);
    tip.scale = 0.06f;
    ph.petioles[0].leaves = {tip};
    EXPECT_FLOAT_EQ(leafSizeRatio(ph, nominalReciprocal(RandomFloat::uniform(0.0f, 0.2f))), 1.0f);
    EXPECT_FLOAT_EQ(leafSizeRatio(ph, nominalReciprocal(RandomFloat(0.0f))), 1.0f);
    // A normal draw: the reciprocal of its mean.
    EXPECT_NEAR(nominalReciprocal(RandomFloat::normal(0.1f, 0.01f)), 10.0, 1e-5);
}

TEST(LeafExpansion, GrowthStepIsTheShortestPhyllochronOfThePlantsTypes) {
    PlantInstance plant;
    EXPECT_EQ(growthStep(plant), 1.0);
    ShootParameters a, b;
    a.phyllochron_min = 3.0f;
    b.phyllochron_min = RandomFloat::uniform(1.5f, 2.5f);
    plant.shootTypes["a"] = a;
    EXPECT_EQ(growthStep(plant), 3.0);
    plant.shootTypes["b"] = b;
    EXPECT_EQ(growthStep(plant), 2.0);
}

// A library plant whose leaf rule scales its first leaves: the lowest leaf of a 30-day seedling
// is at the level the law gives, and growing it in 30 one-day calls gives the same leaves.
TEST(LeafExpansion, ALibrarySeedlingsFirstLeafLevelsOffAndCallsDoNotMatter) {
    struct Grown {
        std::unique_ptr<Context> context = std::make_unique<Context>();
        std::unique_ptr<PlantArchitecture> arch;
        unsigned plant = 0;
        std::vector<float> sizes;
    };
    auto grow = [](int calls) {
        Grown g;
        g.arch = std::make_unique<PlantArchitecture>(g.context.get());
        g.arch->setSeed(5);
        g.arch->loadPlantModelFromLibrary("tomato");
        g.plant = g.arch->buildPlantInstanceFromLibrary(vec3(0.0f), 0.0f);
        for (int i = 0; i < calls; ++i) g.arch->advanceTime(g.plant, 30.0 / double(calls));
        for (const Shoot& s : g.arch->plant(g.plant).shoots)
            for (const Phytomer& ph : s.phytomers)
                for (const Petiole& pt : ph.petioles)
                    for (const LeafOrgan& l : pt.leaves) g.sizes.push_back(currentLeafSize(ph, l));
        return g;
    };
    const Grown once = grow(1);
    const Grown daily = grow(30);
    ASSERT_FALSE(once.sizes.empty());
    EXPECT_EQ(once.sizes, daily.sizes);
    // Step 2 days (the phyllochron), rate 0.1, nominal size uniform(0.12, 0.18): a leaf drawn
    // at P and scaled by c has r = c P ln(1.5) / 0.06. The first node is made on day 0 at
    // c = 0.5 (the species' rule min(1, 0.5 + 0.5 age / 10)): r is 0.41 to 0.61, so its leaf
    // levels off at 0.2 r / (1 - r) = 0.14 to 0.31 of its full size, the level it is at
    // after 15 steps.
    const std::vector<Phytomer>& nodes = once.arch->plant(once.plant).shoots[0].phytomers;
    ASSERT_GT(nodes.size(), 10u);
    EXPECT_GT(nodes[0].leafFraction, 0.13f);
    EXPECT_LT(nodes[0].leafFraction, 0.32f);
    // Nodes made on days 10 to 14 (c = 1, r 0.81 to 1.22) are at least 8 steps old: at least
    // 0.81^8 0.01 + 0.2 x 0.81 (1 - 0.81^8) / 0.19 = 0.69 of full size.
    int checked = 0;
    for (const Phytomer& ph : nodes)
        if (ph.birth >= 10.0 && ph.birth <= 14.0) {
            EXPECT_GT(ph.leafFraction, 0.69f) << ph.birth;
            ++checked;
        }
    EXPECT_GE(checked, 2);
}
