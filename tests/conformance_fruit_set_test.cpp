// Fruit set follows fruit_set_probability, as the specification states: "fruit_set_probability
// determines the probability a flower will set into a fruit", and flowers "turn into fruit
// after a time of time_to_fruit_set following the time of the previous phenological
// transition" (here flower opening).
//
// A hand-built stem of known flower count: every node has one floral bud that flowers (flower
// bud break probability 1) with a fixed number of flowers, and nothing else grows. The open
// flowers are counted before fruit set and the fruit after it.

#include <gtest/gtest.h>

#include <cmath>

#include "plantarch/PlantArchitecture.h"

using namespace plantarch;

namespace {

constexpr unsigned kNodes = 40;
constexpr int kFlowersPerBud = 5;
constexpr float kOpening = 2.0f;   // days after dormancy break (at age 0)
constexpr float kFruitSet = 3.0f;  // days after opening

struct FlowerCount {
    std::size_t open = 0, closed = 0, fruit = 0, buds = 0;
};

FlowerCount countFlowers(const PlantInstance& p) {
    FlowerCount c;
    for (const Shoot& s : p.shoots)
        for (const Phytomer& ph : s.phytomers)
            for (const Petiole& pt : ph.petioles)
                for (const FloralBud& fb : pt.floralBuds) {
                    ++c.buds;
                    if (fb.stage == FloralStage::FlowerOpen) c.open += fb.flowers.size();
                    if (fb.stage == FloralStage::FlowerClosed) c.closed += fb.flowers.size();
                    if (fb.stage == FloralStage::Fruit) c.fruit += fb.flowers.size();
                }
    return c;
}

struct Orchard {
    Context ctx;
    PlantArchitecture arch{&ctx};
    std::vector<unsigned> plants;

    Orchard(float fruitSetProbability, unsigned plantCount, std::uint64_t seed) {
        ShootParameters s;
        s.max_nodes = int(kNodes);  // the stem is built whole: no new phytomers
        s.phytomer_parameters.internode.max_vegetative_buds_per_petiole = 0;
        s.phytomer_parameters.internode.max_floral_buds_per_petiole = 1;
        s.phytomer_parameters.inflorescence.flowers_per_peduncle = kFlowersPerBud;
        s.flower_bud_break_probability = 1.0f;
        s.fruit_set_probability = fruitSetProbability;
        s.determinate_shoot_growth = false;
        arch.defineShootType("stem", s);
        PhenologyParameters ph;
        ph.time_to_dormancy_break = 0.0f;
        ph.time_to_flower_initiation = -1.0f;
        ph.time_to_flower_opening = kOpening;
        ph.time_to_fruit_set = kFruitSet;
        ph.time_to_fruit_maturity = 10.0f;
        arch.setDefaultPhenology(ph);
        arch.setSeed(seed);
        for (unsigned i = 0; i < plantCount; ++i) {
            const unsigned id = arch.addPlantInstance(vec3(float(i), 0.0f, 0.0f), 0.0f);
            arch.addBaseStemShoot(
                id,
                {.phytomers = kNodes, .size = {.internodeLengthMax = 0.02f}, .shootType = "stem"});
            plants.push_back(id);
        }
    }
    FlowerCount count() const {
        FlowerCount total;
        for (unsigned id : plants) {
            const FlowerCount c = countFlowers(arch.plant(id));
            total.open += c.open;
            total.closed += c.closed;
            total.fruit += c.fruit;
            total.buds += c.buds;
        }
        return total;
    }
};

// Grows the orchard to just before fruit set, counts the open flowers (the flowers that can
// set), grows past fruit set and returns (open flowers before, fruit after).
std::pair<std::size_t, std::size_t> openFlowersThenFruit(Orchard& o) {
    o.arch.advanceTime(kOpening + kFruitSet - 0.5);
    const FlowerCount before = o.count();
    EXPECT_EQ(before.fruit, 0u) << "fruit before opening + time_to_fruit_set";
    EXPECT_EQ(before.closed, 0u);
    EXPECT_EQ(before.open, o.plants.size() * kNodes * kFlowersPerBud) << "every bud flowers";
    o.arch.advanceTime(1.0);
    const FlowerCount after = o.count();
    EXPECT_EQ(after.open, 0u) << "every open flower set fruit or fell at fruit set";
    return {before.open, after.fruit};
}

// The fraction of n independent flowers that set fruit lies in the binomial 99.9 % interval
// about p: n p +- 3.29 sqrt(n p (1 - p)) fruit (normal approximation, good here: n p (1 - p)
// is over 400). A correct model fails this for one seed in a thousand.
void expectBinomial(float p, std::uint64_t seed) {
    Orchard o(p, 10, seed);
    const auto [flowers, fruit] = openFlowersThenFruit(o);
    ASSERT_EQ(flowers, 2000u);
    const double n = double(flowers);
    const double halfWidth = 3.2905 * std::sqrt(n * p * (1.0 - p));
    EXPECT_NEAR(double(fruit), n * p, halfWidth)
        << "p = " << p << ": " << fruit << " of " << flowers << " flowers set fruit";
}

TEST(ConformanceFruitSet, FractionOfFlowersSettingFruitIsTheProbability) {
    expectBinomial(0.3f, 1);
    expectBinomial(0.3f, 2);
    expectBinomial(0.8f, 3);
    expectBinomial(0.8f, 4);
}

TEST(ConformanceFruitSet, ProbabilityZeroSetsNoFruitAndOneSetsEveryFlower) {
    Orchard none(0.0f, 2, 5);
    const auto [flowersNone, fruitNone] = openFlowersThenFruit(none);
    EXPECT_EQ(flowersNone, 400u);
    EXPECT_EQ(fruitNone, 0u);
    for (unsigned id : none.plants)
        EXPECT_TRUE(none.arch.getPlantObjectIDs(id, OrganKind::Fruit).empty());

    Orchard all(1.0f, 2, 6);
    const auto [flowersAll, fruitAll] = openFlowersThenFruit(all);
    EXPECT_EQ(flowersAll, 400u);
    EXPECT_EQ(fruitAll, flowersAll);
    for (unsigned id : all.plants)
        EXPECT_FALSE(all.arch.getPlantObjectIDs(id, OrganKind::Fruit).empty());
}

}  // namespace
